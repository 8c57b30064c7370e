//! Shader snippets (of test tables and of every default preset's table): the WGSL is parsed
//! and validated by naga (full validation) as generated and inside a module
//! that calls it from a fragment shader; the GLSL is validated by naga's GLSL frontend inside
//! a `#version 450` fragment shader (naga reads only Vulkan-style separate textures and
//! samplers, so the combined-sampler parameters are rewritten mechanically into a texture and
//! a sampler, and the `highp` qualifiers dropped, first); the HLSL signatures are checked as
//! text. The real compilers of each language (glslang for GLSL ES, desktop and Vulkan GLSL and
//! HLSL, spirv-val on their SPIR-V) run in tests/shader_compilers.rs. The coordinate transform is
//! checked numerically: `texture_coordinates` fed into an emulated GPU fetch (linear
//! filtering of normalized coordinates, clamp-to-edge) equals `Lut::lookup`.

use brdfbake::encode::shader::{
    lookup_function_name, texture_coordinates, ShaderLang, ShaderSnippet,
};
use brdfbake::encode::Encoder;
use brdfbake::lut::{Axis, Channel, Convention, Lut, Quantity};
use brdfbake::model::RoughnessQuantity;
use naga::valid::{Capabilities, ValidationFlags, Validator};

#[path = "common/defaults.rs"]
mod defaults;

fn axis(name: &str, size: usize, range: [f64; 2], convention: Convention) -> Axis {
    Axis {
        name: name.into(),
        quantity: if name == "roughness" {
            Quantity::Roughness(RoughnessQuantity::Perceptual)
        } else if name == "exponent" {
            Quantity::Roughness(RoughnessQuantity::BlinnPhongExponent)
        } else {
            Quantity::Cosine
        },
        size,
        range,
        convention,
        warp: Default::default(),
        clamp: None,
    }
}

/// EEVEE's `btdf_split_sum_ggx` axes, smaller: η² along u (a `square` warp, η clamped),
/// the view cosine in the critical-angle remap of each texel's η along v, roughness slices.
fn critical_angle_axes(convention: Convention) -> Vec<Axis> {
    use brdfbake::lut::Warp;
    use brdfbake::model::FresnelQuantity;
    vec![
        Axis {
            quantity: Quantity::Fresnel(FresnelQuantity::Eta),
            warp: Warp::Square,
            clamp: Some([1e-4, 1.0]),
            ..axis("fresnel", 6, [0.0, 1.0], convention)
        },
        Axis {
            warp: Warp::CriticalAngle,
            clamp: Some([1e-4, 0.9999]),
            ..axis("cos_theta_v", 8, [0.0, 1.0], convention)
        },
        axis("roughness", 4, [0.0, 1.0], convention),
    ]
}

/// A table with pseudo-random texels (so that any index mix-up shows).
fn lut(axes: Vec<Axis>, nc: usize) -> Lut {
    let n: usize = axes.iter().map(|a| a.size).product();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let data = (0..n * nc)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32 * 4.0 - 1.0
        })
        .collect();
    Lut {
        axes,
        channels: (0..nc)
            .map(|c| Channel {
                name: ["A", "B", "C", "D"][c].into(),
                meaning: format!("test channel {c}"),
            })
            .collect(),
        data,
        error_estimate: vec![0.0; nc],
        evaluations: 0,
    }
}

/// Test tables: (name, table), covering 1 to 3 axes, 1 to 4 channels, both conventions,
/// ranges not starting at 0, and a single-texel axis.
fn tables() -> Vec<(&'static str, Lut)> {
    use Convention::{Centers, Endpoints};
    vec![
        (
            "dfg",
            lut(
                vec![
                    axis("cos_theta_v", 8, [0.0, 1.0], Centers),
                    axis("roughness", 6, [0.05, 1.0], Endpoints),
                ],
                2,
            ),
        ),
        (
            "dfg-cloth",
            lut(
                vec![
                    axis("cos_theta_v", 5, [0.0, 1.0], Endpoints),
                    axis("roughness", 7, [0.0, 1.0], Centers),
                ],
                3,
            ),
        ),
        (
            "ndf4",
            lut(
                vec![
                    axis("cos_theta_h", 9, [0.25, 1.0], Centers),
                    axis("exponent", 4, [1.0, 1000.0], Endpoints),
                ],
                4,
            ),
        ),
        (
            "albedo-avg",
            lut(vec![axis("roughness", 10, [0.1, 0.9], Endpoints)], 1),
        ),
        (
            "g2",
            lut(
                vec![
                    axis("cos_theta_v", 4, [0.0, 1.0], Centers),
                    axis("cos_theta_l", 5, [0.0, 1.0], Endpoints),
                    axis("roughness", 3, [0.2, 1.0], Centers),
                ],
                1,
            ),
        ),
        (
            "vgroove",
            lut(
                vec![
                    axis("n_dot_l", 3, [0.0, 1.0], Endpoints),
                    axis("n_dot_h", 4, [0.0, 1.0], Centers),
                    axis("n_dot_v", 5, [0.1, 1.0], Endpoints),
                ],
                2,
            ),
        ),
        ("btdf-critical", lut(critical_angle_axes(Endpoints), 2)),
        (
            "single",
            lut(
                vec![
                    axis("cos_theta", 6, [0.0, 1.0], Centers),
                    axis("roughness", 1, [0.5, 0.5], Centers),
                ],
                1,
            ),
        ),
    ]
}

fn attributes(name: &str) -> Vec<(String, String)> {
    vec![
        ("schema".into(), "brdfbake.lut/1".into()),
        ("table".into(), name.into()),
        (
            "formula".into(),
            "E(μ) = ∫ f cos θ dω, a line ending in \\".into(),
        ),
        ("multi".into(), "first line\nsecond line */ /*".into()),
    ]
}

fn snippet(lang: ShaderLang, name: &str, lut: &Lut, attrs: &[(String, String)]) -> String {
    let s = ShaderSnippet {
        lang,
        table_name: name.into(),
    };
    let bytes = s.encode(lut, attrs).unwrap();
    assert_eq!(s.encode(lut, attrs).unwrap(), bytes, "deterministic");
    String::from_utf8(bytes).unwrap()
}

fn validate(module: &naga::Module, source: &str, what: &str) {
    if let Err(e) = Validator::new(ValidationFlags::all(), Capabilities::all()).validate(module) {
        panic!(
            "{what}: naga validation failed:\n{}\n{source}",
            e.emit_to_string(source)
        );
    }
}

fn parse_wgsl(source: &str, what: &str) -> naga::Module {
    naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{what}: {}\n{source}", e.emit_to_string(source)))
}

/// The functions of a table's snippet: (name, texture kind).
fn functions(name: &str, lut: &Lut) -> Vec<(String, &'static str)> {
    let f = lookup_function_name(name);
    if lut.axes.len() == 3 {
        vec![(f.clone(), "3d"), (format!("{f}_array"), "array")]
    } else {
        vec![(f, "2d")]
    }
}

/// Arguments for the axes of a call: the first components of `coords`.
fn axis_args(lut: &Lut) -> String {
    (0..lut.axes.len())
        .map(|k| format!("coords.{}", ["x", "y", "z"][k]))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Header attributes of a snippet.
type Attributes = Vec<(String, String)>;

/// The tables the naga checks run on, with the attribute sets of their snippets: the test
/// tables with none, the test attributes and a scale; every default preset's table with its
/// own header attributes.
fn naga_cases(scale: &str) -> Vec<(String, Lut, Vec<Attributes>)> {
    let mut v: Vec<_> = tables()
        .into_iter()
        .map(|(name, lut)| {
            let sets = vec![
                vec![],
                attributes(name),
                vec![("scale".to_string(), scale.to_string())],
            ];
            (name.to_string(), lut, sets)
        })
        .collect();
    for (preset, t) in defaults::tables() {
        let lut = defaults::shaped_lut(&t);
        let attrs = brdfbake::meta::header_attributes(&preset, &t, &lut);
        v.push((t.spec.name.clone(), lut, vec![attrs]));
    }
    v
}

#[test]
fn wgsl_snippets_validate_with_naga() {
    for (name, lut, sets) in naga_cases("0.001") {
        let name = name.as_str();
        for attrs in sets {
            let src = snippet(ShaderLang::Wgsl, name, &lut, &attrs);
            let module = parse_wgsl(&src, name);
            validate(&module, &src, name);

            // called from a fragment shader with bound resources
            let nc = lut.channels.len();
            let mut wrapper = src.clone();
            let widen = |v: &str| match nc {
                1 => format!("vec4<f32>({v}, 0.0, 0.0, 1.0)"),
                2 => format!("vec4<f32>({v}, 0.0, 1.0)"),
                3 => format!("vec4<f32>({v}, 1.0)"),
                _ => v.to_string(),
            };
            let mut body = String::from("    var out = vec4<f32>(0.0);\n");
            for (i, (f, kind)) in functions(name, &lut).iter().enumerate() {
                let ty = match *kind {
                    "3d" => "texture_3d<f32>",
                    "array" => "texture_2d_array<f32>",
                    _ => "texture_2d<f32>",
                };
                wrapper.push_str(&format!(
                    "@group(0) @binding({}) var tex{i}: {ty};\n",
                    2 * i + 1
                ));
                let call = format!("{f}(tex{i}, smp, {})", axis_args(&lut));
                body.push_str(&format!("    out += {};\n", widen(&call)));
            }
            wrapper.push_str(&format!(
                "@group(0) @binding(0) var smp: sampler;\n\
                 @fragment\nfn main(@location(0) coords: vec4<f32>) -> @location(0) vec4<f32> {{\n{body}    return out;\n}}\n"
            ));
            let module = parse_wgsl(&wrapper, name);
            validate(&module, &wrapper, name);
            assert_eq!(module.entry_points.len(), 1);
        }
    }
}

/// Rewrites the combined-sampler parameters of a GLSL snippet into a separate texture and
/// sampler (`highp sampler2D lut` → `texture2D lut_texture, sampler lut_sampler`, and
/// `textureLod(lut, …)` → `textureLod(sampler2D(lut_texture, lut_sampler), …)`), the only
/// form naga's GLSL frontend reads, and drops the `highp` qualifiers, which it does not read
/// on parameters (glslang compiles the snippets as written: tests/shader_compilers.rs).
fn separate_samplers(src: &str) -> String {
    let mut out = String::new();
    let mut current = "";
    for line in src.lines() {
        let mut line = line.to_string();
        if !line.starts_with("//") {
            for (combined, texture) in [
                ("sampler2DArray", "texture2DArray"),
                ("sampler2D", "texture2D"),
                ("sampler3D", "texture3D"),
            ] {
                let param = format!("(highp {combined} lut,");
                if line.contains(&param) {
                    current = combined;
                    line = line.replace(
                        &param,
                        &format!("({texture} lut_texture, sampler lut_sampler,"),
                    );
                }
            }
            line = line.replace(
                "textureLod(lut, ",
                &format!("textureLod({current}(lut_texture, lut_sampler), "),
            );
            line = line.replace("highp ", "");
        }
        out.push_str(&line);
        out.push('\n');
    }
    out
}

#[test]
fn glsl_snippets_validate_with_naga() {
    for (name, lut, sets) in naga_cases("1e3") {
        let name = name.as_str();
        for attrs in sets {
            let src = snippet(ShaderLang::Glsl, name, &lut, &attrs);
            let nc = lut.channels.len();
            let widen = |v: &str| match nc {
                1 => format!("vec4({v}, 0.0, 0.0, 1.0)"),
                2 => format!("vec4({v}, 0.0, 1.0)"),
                3 => format!("vec4({v}, 1.0)"),
                _ => v.to_string(),
            };
            let mut shader = String::from(
                "#version 450\n\
                 layout(location = 0) in vec4 coords;\n\
                 layout(location = 0) out vec4 color;\n\
                 layout(set = 0, binding = 0) uniform sampler smp;\n",
            );
            let mut body = String::from("    color = vec4(0.0);\n");
            for (i, (f, kind)) in functions(name, &lut).iter().enumerate() {
                let (texture, combined) = match *kind {
                    "3d" => ("texture3D", "sampler3D"),
                    "array" => ("texture2DArray", "sampler2DArray"),
                    _ => ("texture2D", "sampler2D"),
                };
                assert!(
                    src.contains(&format!("{f}(highp {combined} lut, ")),
                    "{f} takes a {combined}\n{src}"
                );
                shader.push_str(&format!(
                    "layout(set = 0, binding = {}) uniform {texture} tex{i};\n",
                    i + 1
                ));
                let call = format!("{f}(tex{i}, smp, {})", axis_args(&lut));
                body.push_str(&format!("    color += {};\n", widen(&call)));
            }
            shader.push_str(&separate_samplers(&src));
            shader.push_str(&format!("void main()\n{{\n{body}}}\n"));
            let module = naga::front::glsl::Frontend::default()
                .parse(
                    &naga::front::glsl::Options::from(naga::ShaderStage::Fragment),
                    &shader,
                )
                .unwrap_or_else(|e| panic!("{name}: {}\n{shader}", e.emit_to_string(&shader)));
            validate(&module, &shader, name);
        }
    }
}

#[test]
fn hlsl_snippets_have_the_documented_signatures() {
    for (name, lut) in tables() {
        let src = snippet(ShaderLang::Hlsl, name, &lut, &attributes(name));
        let nc = lut.channels.len();
        let ret = if nc == 1 {
            "float".to_string()
        } else {
            format!("float{nc}")
        };
        let params: Vec<String> = lut
            .axes
            .iter()
            .map(|a| format!("float {}", a.name))
            .collect();
        for (f, kind) in functions(name, &lut) {
            let texture = match kind {
                "3d" => "Texture3D<float4>",
                "array" => "Texture2DArray<float4>",
                _ => "Texture2D<float4>",
            };
            let signature = format!(
                "{ret} {f}({texture} lut, SamplerState lut_sampler, {})\n{{\n",
                params.join(", ")
            );
            assert!(src.contains(&signature), "{signature}\n{src}");
        }
        let code: String = src
            .lines()
            .filter(|l| !l.starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n");
        assert_eq!(code.matches('{').count(), code.matches('}').count());
        assert_eq!(code.matches('(').count(), code.matches(')').count());
        assert!(code.contains(".SampleLevel(lut_sampler, "));
        assert!(!code.contains("sampler2D"));
    }
}

#[test]
fn snippets_document_sampling_and_hold_the_transform_constants() {
    for (name, lut) in tables() {
        for lang in [ShaderLang::Glsl, ShaderLang::Hlsl, ShaderLang::Wgsl] {
            let src = snippet(lang, name, &lut, &attributes(name));
            for needle in [
                "linear min and mag filtering, clamp-to-edge",
                "no mipmaps",
                "no y-flip",
                "schema: brdfbake.lut/1",
                "formula: E(μ) = ∫ f cos θ dω, a line ending in \\ (end of line)",
                "//       second line */ /*",
            ] {
                assert!(src.contains(needle), "{name} {lang:?}: {needle}\n{src}");
            }
            for c in &lut.channels {
                assert!(src.contains(&format!("= {}: {}", c.name, c.meaning)));
            }
            for (k, a) in lut.axes.iter().enumerate() {
                assert!(src.contains(&format!("convention {}", a.convention.name())));
                let [lo, hi] = a.range;
                let lit = |v: f64| {
                    let s = format!("{:?}", v as f32);
                    if s.contains('.') {
                        s
                    } else {
                        format!("{s}.0")
                    }
                };
                if a.size == 1 {
                    assert!(src.contains(&format!("s{k}_ = 0.5;")), "{src}");
                    continue;
                }
                // (a warped axis' parameter is p = warp(x), in a local of its own)
                let p = if a.warp == brdfbake::lut::Warp::Linear {
                    a.name.clone()
                } else {
                    format!("p{k}_")
                };
                let t = format!(
                    "clamp(({} - {}) / ({} - {}), 0.0, 1.0);",
                    p,
                    lit(lo),
                    lit(hi),
                    lit(lo)
                );
                assert!(src.contains(&t), "{t}\n{src}");
                let s = match a.convention {
                    Convention::Centers => format!("s{k}_ = t{k}_;"),
                    Convention::Endpoints => {
                        format!("s{k}_ = (0.5 + t{k}_ * {}.0) / {}.0;", a.size - 1, a.size)
                    }
                };
                assert!(src.contains(&s), "{s}\n{src}");
            }
            let scaled = snippet(lang, name, &lut, &[("scale".into(), "0.001".into())]);
            assert!(scaled.contains(" / 0.001;"), "{scaled}");
            assert!(!src.contains(" / 0.001;"));
        }
    }
}

/// Emulated hardware filtering along one axis of `n` texels at normalized coordinate `s`:
/// `p = s·n − 0.5`, the two texels around it clamped to the edge, and the weight of the
/// second.
fn filter(s: f64, n: usize) -> (usize, usize, f64) {
    let p = s * n as f64 - 0.5;
    let i = p.floor();
    let f = p - i;
    let clamp = |i: f64| i.clamp(0.0, (n - 1) as f64) as usize;
    (clamp(i), clamp(i + 1.0), f)
}

/// What a GPU returns for a texture of the table sampled at normalized coordinates `s` (one
/// per axis; a 1D table is a texture of height 1 sampled at v = 0.5).
fn gpu_sample(lut: &Lut, s: &[f64]) -> Vec<f64> {
    let mut taps: Vec<(usize, usize, f64)> = (0..3)
        .map(|k| filter(s.get(k).copied().unwrap_or(0.5), lut.dim(k)))
        .collect();
    if lut.axes.len() < 3 {
        taps[2] = (0, 0, 0.0);
    }
    let nc = lut.channels.len();
    let mut out = vec![0.0; nc];
    for corner in 0..8 {
        let mut w = 1.0;
        let mut idx = [0; 3];
        for (k, &(i0, i1, f)) in taps.iter().enumerate() {
            let hi = (corner >> k) & 1 == 1;
            idx[k] = if hi { i1 } else { i0 };
            w *= if hi { f } else { 1.0 - f };
        }
        for (c, o) in out.iter_mut().enumerate() {
            *o += w * lut.texel(idx, c) as f64;
        }
    }
    out
}

/// The 2D-array variant: the slice position `p = clamp(s₂·n − 0.5, 0, n − 1)`, bilinear
/// fetches from layers floor(p) and ceil(p), blended by p − floor(p).
fn array_sample(lut: &Lut, s: &[f64]) -> Vec<f64> {
    let n = lut.dim(2);
    let p = (s[2] * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
    let (l0, l1) = (p.floor(), p.ceil());
    let layer = |l: usize| -> Vec<f64> {
        let (x0, x1, fx) = filter(s[0], lut.dim(0));
        let (y0, y1, fy) = filter(s[1], lut.dim(1));
        (0..lut.channels.len())
            .map(|c| {
                let t = |x, y| lut.texel([x, y, l], c) as f64;
                (1.0 - fy) * ((1.0 - fx) * t(x0, y0) + fx * t(x1, y0))
                    + fy * ((1.0 - fx) * t(x0, y1) + fx * t(x1, y1))
            })
            .collect()
    };
    let (a, b) = (layer(l0 as usize), layer(l1 as usize));
    a.iter()
        .zip(&b)
        .map(|(a, b)| a + (b - a) * (p - l0))
        .collect()
}

/// Physical test points along an axis: a grid from 30 % below to 30 % above the range, every
/// texel coordinate, midpoints between texels, and the range ends.
fn points(a: &Axis) -> Vec<f64> {
    let [lo, hi] = a.range;
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut v: Vec<f64> = (0..=23)
        .map(|i| lo - 0.3 * span + 1.6 * span * i as f64 / 23.0)
        .collect();
    v.extend(a.coords());
    v.extend((1..a.size).map(|i| 0.5 * (a.coord(i - 1) + a.coord(i))));
    v.extend([lo, hi, lo - 1e-9, hi + 1e-9]);
    v
}

#[test]
fn texture_coordinates_reproduce_the_reference_lookup() {
    let mut checked = 0;
    for (name, lut) in tables() {
        let pts: Vec<Vec<f64>> = lut.axes.iter().map(points).collect();
        let dims: Vec<usize> = pts.iter().map(|p| p.len()).collect();
        let total: usize = dims.iter().product();
        for i in 0..total {
            let mut r = i;
            let x: Vec<f64> = pts
                .iter()
                .map(|p| {
                    let v = p[r % p.len()];
                    r /= p.len();
                    v
                })
                .collect();
            let s = texture_coordinates(&lut, &x);
            assert_eq!(s.len(), lut.axes.len());
            assert!(s.iter().all(|s| (0.0..=1.0).contains(s)), "{s:?}");
            let want = lut.lookup(&x);
            let mut got = vec![gpu_sample(&lut, &s)];
            if lut.axes.len() == 3 {
                got.push(array_sample(&lut, &s));
            }
            for g in got {
                for (c, (g, w)) in g.iter().zip(&want).enumerate() {
                    assert!(
                        (g - w).abs() <= 1e-12,
                        "{name} at {x:?} (s = {s:?}), channel {c}: {g} vs lookup {w}"
                    );
                }
            }
            checked += 1;
        }
    }
    assert!(checked > 10_000, "{checked}");
}

#[test]
fn texture_coordinates_at_the_range_ends() {
    let lut = lut(
        vec![
            axis("cos_theta_v", 8, [0.0, 1.0], Convention::Centers),
            axis("roughness", 6, [0.05, 1.0], Convention::Endpoints),
        ],
        1,
    );
    // endpoints: the range ends are the first and last texel centres
    let s = texture_coordinates(&lut, &[0.0, 0.05]);
    assert_eq!(s, [0.0, 0.5 / 6.0]);
    let s = texture_coordinates(&lut, &[1.0, 1.0]);
    assert_eq!(s, [1.0, 5.5 / 6.0]);
    // out of range: clamped
    assert_eq!(
        texture_coordinates(&lut, &[-3.0, 7.0]),
        texture_coordinates(&lut, &[0.0, 1.0])
    );
}
