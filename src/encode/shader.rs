//! Shader snippets: GLSL, HLSL and WGSL functions that sample a table's texture at physical
//! coordinates (`n·v`, roughness, … in each axis' own quantity and convention) and return the
//! table's channels, with the exact texture-coordinate transform of every axis built in.
//!
//! Per axis `k` with range `[lo, hi]` of its parameter `p` and `N` texels the snippets
//! compute, in f32, `p = x` (linear axes), `√(1 − x)`, `√x` or `acos x` (warped cosine axes,
//! `x` first clamped to [0, 1]), `t = clamp((p − lo)/(hi − lo), 0, 1)` and sample at `s = t` (centers convention) or
//! `s = (0.5 + t·(N − 1))/N` (endpoints convention); an axis of a single texel is sampled at
//! `s = 0.5`. [`texture_coordinates`] computes the same in f64, for tests and for engines that
//! compute coordinates on the CPU.
//!
//! Functions (`NAME` = the table name, sanitized as in [`super::source`], lower case):
//! - 1D and 2D tables: `NAME_lookup(texture, [sampler,] x0[, x1])`, sampling a 2D texture
//!   (a 1D table is a 2D texture of height 1, as the EXR file stores it; it is sampled at
//!   v = 0.5).
//! - 3D tables: `NAME_lookup` on a 3D texture, and `NAME_lookup_array` on a 2D array texture
//!   whose layer z holds slice z: two bilinear fetches from the layers `floor(p)` and
//!   `ceil(p)` around the slice position `p = clamp(s₂·N₂ − 0.5, 0, N₂ − 1)`, blended by
//!   `p − floor(p)` — what a 3D texture's linear filter does along w.
//!
//! The return type follows the channel count (float, vec2, vec3, vec4 and their HLSL/WGSL
//! spellings): a 3-channel table stored in a 4-channel texture (KTX2/WebGPU have no
//! 3-channel float formats) returns `.rgb`; a 1-channel table returns `.r`.
//!
//! A `scale` attribute other than 1 (stored texel = value × scale, see the presets' `scale`)
//! makes the functions divide what they sample by it, so they return the values as computed.
//!
//! GLSL functions take `sampler2D`/`sampler3D`/`sampler2DArray` and compile as written in GLSL
//! ES 3.00 (WebGL2), OpenGL GLSL 3.30 to 4.60 core and Vulkan GLSL (combined image samplers):
//! every declaration they make (parameters, locals, the return type) is `highp`, because GLSL
//! ES gives `sampler3D` and `sampler2DArray` no default precision, `sampler2D` a default of
//! `lowp`, and a fragment shader's floats the precision its own `precision` statement says
//! (often `mediump`, ~3 decimal digits: too coarse for texture coordinates). Desktop and Vulkan
//! GLSL accept the qualifiers and ignore them. HLSL and WGSL functions take a texture and a
//! sampler. All sample mip level 0 explicitly, so they work in any shader stage.

use super::source::{
    attribute_lines, axis_lines, check_table, comment_lines, identifier, scale_attribute,
};
use super::{shader_ltc, EncodeError, Encoder};
use crate::lut::{Axis, Convention, Lut, Warp};
use std::fmt::Write as _;

/// A shading language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShaderLang {
    Glsl,
    Hlsl,
    Wgsl,
}

impl ShaderLang {
    pub fn name(self) -> &'static str {
        match self {
            ShaderLang::Glsl => "GLSL",
            ShaderLang::Hlsl => "HLSL",
            ShaderLang::Wgsl => "WGSL",
        }
    }
}

/// Encodes a table's lookup function in one shading language.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShaderSnippet {
    pub lang: ShaderLang,
    /// The table's name: the source of the function names, and used in error messages.
    pub table_name: String,
}

/// The note on a normalized-integer `storage` attribute (written for unorm8/unorm16 tables
/// only): the sampler returns the stored values in [0, 1] as they are, so the functions need
/// nothing more — but the texture must be uploaded in a UNORM format.
fn storage_note(attributes: &[(String, String)]) -> Option<String> {
    let (_, v) = attributes.iter().find(|(k, _)| k == "storage")?;
    let (bits, max, formats) = match v.as_str() {
        "unorm8" => (8, 255, "R8/RG8/RGBA8 UNORM: r8unorm, rg8unorm, rgba8unorm"),
        "unorm16" => (
            16,
            65535,
            "R16/RG16/RGBA16 UNORM: r16unorm, rg16unorm, rgba16unorm",
        ),
        _ => return None,
    };
    Some(format!(
        "  (storage {v}: the texture holds {bits}-bit normalized integers, code = round(value x {max}), \
         uploaded as {formats}; the sampler returns code / {max} in [0, 1], the stored value, so no \
         conversion is needed; each texel is off by at most half a step, 1/{})",
        2 * max
    ))
}

/// The normalized texture coordinates the snippets sample for physical coordinates `x` (one
/// per axis, in each axis' own quantity), computed in f64: per axis
/// `t = clamp((x − lo)/(hi − lo), 0, 1)`, then `s = t` (centers) or `s = (0.5 + t·(N − 1))/N`
/// (endpoints); `s = 0.5` for an axis of one texel. One coordinate per axis: a 1D table's
/// texture is additionally sampled at v = 0.5, and the 2D-array variant of a 3D table turns
/// the third coordinate into the layer position `clamp(s·N − 0.5, 0, N − 1)`.
///
/// # Panics
/// If `x` does not hold one coordinate per axis.
pub fn texture_coordinates(lut: &Lut, x: &[f64]) -> Vec<f64> {
    assert_eq!(x.len(), lut.axes.len(), "one coordinate per axis");
    let c = crate::lut::critical_cosine_at(&lut.axes, x);
    lut.axes
        .iter()
        .zip(x)
        .map(|(a, &x)| {
            if a.size == 1 {
                return 0.5;
            }
            let t = a.normalized_at(x, c);
            match a.convention {
                Convention::Centers => t,
                Convention::Endpoints => (0.5 + t * (a.size - 1) as f64) / a.size as f64,
            }
        })
        .collect()
}

/// The name of the lookup function of table `table_name` (`dfg` → `dfg_lookup`); the 2D-array
/// variant of a 3D table appends `_array`.
pub fn lookup_function_name(table_name: &str) -> String {
    format!("{}_lookup", identifier(table_name).to_ascii_lowercase())
}

impl Encoder for ShaderSnippet {
    fn extension(&self) -> &'static str {
        match self.lang {
            ShaderLang::Glsl => "glsl",
            ShaderLang::Hlsl => "hlsl",
            ShaderLang::Wgsl => "wgsl",
        }
    }

    fn encode(&self, lut: &Lut, attributes: &[(String, String)]) -> Result<Vec<u8>, EncodeError> {
        check_table(&self.table_name, lut)?;
        let nc = lut.channels.len();
        if nc > 4 {
            return Err(EncodeError::Shape {
                table: self.table_name.clone(),
                reason: format!("a texture holds at most 4 channels, the table has {nc}"),
            });
        }
        let params = parameter_names(lut);
        let name = lookup_function_name(&self.table_name);
        let g = Gen {
            lang: self.lang,
            lut,
            params: &params,
            scale: scale_attribute(attributes),
        };
        // an `ltc` table's area-light functions
        let kind = attributes
            .iter()
            .find(|(k, _)| k == "kind")
            .map(|(_, v)| v.as_str());
        let ltc = shader_ltc::applies(lut, kind).then(|| shader_ltc::Context {
            lang: match self.lang {
                ShaderLang::Glsl => shader_ltc::Lang::Glsl,
                ShaderLang::Hlsl => shader_ltc::Lang::Hlsl,
                ShaderLang::Wgsl => shader_ltc::Lang::Wgsl,
            },
            prefix: identifier(&self.table_name).to_ascii_lowercase(),
            handles: g.handles(Storage::Texture2d),
            handle_args: match self.lang {
                ShaderLang::Glsl => TEXTURE.to_string(),
                _ => format!("{TEXTURE}, {SAMPLER}"),
            },
            axis_params: g.axis_params(),
            axis_args: params.clone(),
            lut,
        });
        let mut out = String::new();
        let mut documentation = self.documentation(lut, attributes);
        if let Some(c) = &ltc {
            // before the attributes
            let at = documentation
                .iter()
                .rposition(|l| l == "Table attributes:")
                .map_or(documentation.len(), |i| i - 1);
            let lines = shader_ltc::documentation(c);
            documentation.splice(at..at, lines);
        }
        for line in documentation {
            for l in comment_lines(&line) {
                if l.is_empty() {
                    out.push_str("//\n");
                } else {
                    let _ = writeln!(out, "// {l}");
                }
            }
        }
        out.push('\n');
        match lut.axes.len() {
            3 => {
                out.push_str(&g.function(&name, Storage::Texture3d));
                out.push('\n');
                out.push_str(&g.function(&format!("{name}_array"), Storage::Array));
            }
            _ => out.push_str(&g.function(&name, Storage::Texture2d)),
        }
        if let Some(c) = &ltc {
            out.push('\n');
            out.push_str(&shader_ltc::code(c));
        }
        Ok(out.into_bytes())
    }
}

impl ShaderSnippet {
    /// The comment block (lines without comment markers).
    fn documentation(&self, lut: &Lut, attributes: &[(String, String)]) -> Vec<String> {
        let name = lookup_function_name(&self.table_name);
        let nc = lut.channels.len();
        let mut d = vec![
            format!(
                "brdfbake lookup of table `{}` ({}): generated, do not edit.",
                self.table_name,
                self.lang.name()
            ),
            String::new(),
        ];
        let args: Vec<&str> = lut.axes.iter().map(|a| a.name.as_str()).collect();
        match lut.axes.len() {
            3 => {
                d.push(format!(
                    "{name}({}) samples the table stored as a 3D texture (slice z = depth z);",
                    args.join(", ")
                ));
                d.push(format!(
                    "{name}_array(...) samples it stored as a 2D array texture (layer z = slice z; the EXR \
                     file stacks the slices vertically: slice z is rows [z*{ny}, (z+1)*{ny})), blending \
                     two layers by hand exactly as a 3D texture's linear filter blends slices.",
                    ny = lut.dim(1)
                ));
            }
            2 => d.push(format!(
                "{name}({}) samples the table stored as a 2D texture.",
                args.join(", ")
            )),
            _ => d.push(format!(
                "{name}({}) samples the table stored as a 2D texture of height 1 (sampled at v = 0.5).",
                args.join(", ")
            )),
        }
        d.push(
            "Arguments are physical coordinates in each axis' own quantity; values outside an axis' \
             range are clamped to it (the value at the range end)."
                .into(),
        );
        d.push(String::new());
        d.push("Axes:".into());
        for (k, a) in lut.axes.iter().enumerate() {
            d.extend(axis_lines(k, a));
        }
        d.push(String::new());
        d.push(format!(
            "Returns the table's {nc} channel{} ({}):",
            if nc == 1 { "" } else { "s" },
            self.vector(nc)
        ));
        for (c, ch) in lut.channels.iter().enumerate() {
            d.push(format!(
                "  .{} = {}: {}",
                &"rgba"[c..c + 1],
                ch.name,
                ch.meaning
            ));
        }
        if let Some(s) = scale_attribute(attributes) {
            d.push(format!(
                "  (the texture stores the values times {s}, the `scale` attribute; the functions divide by it)"
            ));
        }
        if nc == 3 {
            d.push(
                "  (a 3-channel table is stored in a 4-channel texture: the 4th channel is padding \
                 and is not returned)"
                    .into(),
            );
        }
        if let Some(note) = storage_note(attributes) {
            d.push(note);
        }
        d.push(String::new());
        d.push(
            "Sampler state: linear min and mag filtering, clamp-to-edge on every axis, no mipmaps \
             (the functions sample level 0)."
                .into(),
        );
        d.push(
            "Orientation: row 0 of the data (y = 0, the first coordinate of axis 1) is v = 0: upload \
             the rows in file order, no y-flip."
                .into(),
        );
        if self.lang == ShaderLang::Glsl {
            d.push(
                "GLSL: compiles as written in GLSL ES 3.00 (WebGL2), GLSL 3.30-4.60 core and Vulkan GLSL \
                 (after your #version line). Every declaration here is highp; in GLSL ES declare the \
                 texture uniform highp too (`uniform highp sampler2D lut;`): ES has no default precision \
                 for sampler3D and sampler2DArray, and defaults sampler2D to lowp."
                    .into(),
            );
        }
        if self.lang == ShaderLang::Wgsl {
            d.push(
                "WebGPU: 32-bit float textures are filterable only with the `float32-filterable` \
                 feature; without it, store the table as f16 (e.g. rgba16float)."
                    .into(),
            );
        }
        d.push(String::new());
        d.push("Table attributes:".into());
        d.extend(attribute_lines(attributes));
        d
    }

    fn vector(&self, nc: usize) -> String {
        vector_type(self.lang, nc)
    }
}

/// How the texture of a table is stored.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Storage {
    Texture2d,
    Texture3d,
    Array,
}

fn vector_type(lang: ShaderLang, n: usize) -> String {
    match (lang, n) {
        (ShaderLang::Glsl, 1) => "float".into(),
        (ShaderLang::Glsl, _) => format!("vec{n}"),
        (ShaderLang::Hlsl, 1) => "float".into(),
        (ShaderLang::Hlsl, _) => format!("float{n}"),
        (ShaderLang::Wgsl, 1) => "f32".into(),
        (ShaderLang::Wgsl, _) => format!("vec{n}<f32>"),
    }
}

/// The precision qualifier of every GLSL declaration (see the module documentation).
const GLSL_PRECISION: &str = "highp";

/// Names of the texture and sampler parameters; axis parameter names never collide with them.
const TEXTURE: &str = "lut";
const SAMPLER: &str = "lut_sampler";

/// The parameter names of the axes: their names as identifiers (lower case, without leading
/// or trailing underscores, so that they never collide with the locals, which end in `_`),
/// made unique.
fn parameter_names(lut: &Lut) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for (k, a) in lut.axes.iter().enumerate() {
        let mut s: String = a
            .name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() {
                    c.to_ascii_lowercase()
                } else {
                    '_'
                }
            })
            .collect();
        // no `__` (reserved in GLSL and WGSL), no leading or trailing `_`
        while s.contains("__") {
            s = s.replace("__", "_");
        }
        let mut s = s.trim_matches('_').to_string();
        if s.is_empty() {
            s = format!("x{k}");
        } else if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
            s.insert_str(0, "x_");
        }
        if names.contains(&s) || s == TEXTURE || s == SAMPLER || s.starts_with("gl_") {
            s = format!("{s}_axis{k}");
        }
        names.push(s);
    }
    names
}

/// A literal of the f32 nearest to `v`, parenthesized when negative.
fn float_literal(v: f64) -> String {
    let mut s = format!("{:?}", v as f32);
    if !s.contains(['.', 'e', 'E']) {
        s.push_str(".0");
    }
    if s.starts_with('-') {
        format!("({s})")
    } else {
        s
    }
}

/// Code generation for one language and table.
struct Gen<'a> {
    lang: ShaderLang,
    lut: &'a Lut,
    params: &'a [String],
    /// The table's `scale` attribute (stored = value × scale), when not 1.
    scale: Option<f64>,
}

impl Gen<'_> {
    /// A local declaration `highp float name = expr;` / `float name = expr;` / `let name = expr;`.
    fn local(&self, name: &str, expr: &str) -> String {
        match self.lang {
            ShaderLang::Wgsl => format!("    let {name} = {expr};\n"),
            ShaderLang::Glsl => format!("    {GLSL_PRECISION} float {name} = {expr};\n"),
            ShaderLang::Hlsl => format!("    float {name} = {expr};\n"),
        }
    }

    /// The statements computing `s{k}_`, the normalized coordinate of axis `k`.
    fn coordinate(&self, k: usize, a: &Axis) -> String {
        let x = &self.params[k];
        if a.size == 1 {
            return self.local(&format!("s{k}_"), "0.5");
        }
        let [lo, hi] = a.range;
        let (lo, hi) = (float_literal(lo), float_literal(hi));
        // the axis' parameter p = warp(x), x first clamped into the warp's domain
        let mut s = String::new();
        let p = match a.warp {
            Warp::Linear => x.clone(),
            w => {
                let xc = match w.coordinate_domain() {
                    Some([dlo, dhi]) => {
                        format!("clamp({x}, {}, {})", float_literal(dlo), float_literal(dhi))
                    }
                    None => x.clone(),
                };
                let expr = match w {
                    Warp::SqrtOneMinus => format!("sqrt(1.0 - {xc})"),
                    Warp::Sqrt => format!("sqrt({xc})"),
                    Warp::Acos => format!("acos({xc})"),
                    Warp::Square => format!("{xc} * {xc}"),
                    Warp::OneMinus => format!("1.0 - {xc}"),
                    Warp::CriticalAngle => {
                        s.push_str(&self.critical_cosine(k));
                        s.push_str(&self.local(&format!("x{k}_"), &xc));
                        // both branches are finite (WGSL's select evaluates both)
                        let below = format!("0.5 * x{k}_ / max(c{k}_, 1e-30)");
                        let above =
                            format!("0.5 + 0.5 * (x{k}_ - c{k}_) / max(1.0 - c{k}_, 1e-30)");
                        let cond = format!("x{k}_ <= c{k}_");
                        match self.lang {
                            ShaderLang::Wgsl => format!("select({above}, {below}, {cond})"),
                            _ => format!("({cond}) ? {below} : {above}"),
                        }
                    }
                    Warp::Linear => unreachable!("handled above"),
                };
                s.push_str(&self.local(&format!("p{k}_"), &expr));
                format!("p{k}_")
            }
        };
        s.push_str(&self.local(
            &format!("t{k}_"),
            &format!("clamp(({p} - {lo}) / ({hi} - {lo}), 0.0, 1.0)"),
        ));
        let expr = match a.convention {
            Convention::Centers => format!("t{k}_"),
            Convention::Endpoints => format!(
                "(0.5 + t{k}_ * {}) / {}",
                float_literal((a.size - 1) as f64),
                float_literal(a.size as f64)
            ),
        };
        s.push_str(&self.local(&format!("s{k}_"), &expr));
        s
    }

    /// The statements computing `c{k}_`, the critical cosine √(1 − η²) (0 for η ≥ 1) of the
    /// relative index η that the table's fresnel axis gives at its (clamped) argument: the
    /// parameter of axis k's critical-angle warp.
    fn critical_cosine(&self, k: usize) -> String {
        use crate::lut::Quantity;
        use crate::model::FresnelQuantity as Q;
        let Some((j, f)) = self
            .lut
            .axes
            .iter()
            .enumerate()
            .find(|(_, a)| a.name == "fresnel")
        else {
            return self.local(&format!("c{k}_"), "0.0");
        };
        let x = &self.params[j];
        let x = match f.clamp {
            Some([lo, hi]) => format!("clamp({x}, {}, {})", float_literal(lo), float_literal(hi)),
            None => x.clone(),
        };
        let eta = match f.quantity {
            Quantity::Fresnel(Q::EtaReflectance) => format!("(1.0 + {x}) / (1.0 - {x})"),
            Quantity::Fresnel(Q::InverseEtaReflectance) => format!("(1.0 - {x}) / (1.0 + {x})"),
            _ => x,
        };
        let mut s = self.local(&format!("eta{k}_"), &eta);
        s.push_str(&self.local(
            &format!("c{k}_"),
            &format!("sqrt(max((1.0 - eta{k}_) * (1.0 + eta{k}_), 0.0))"),
        ));
        s
    }

    fn vec(&self, n: usize, args: &str) -> String {
        format!("{}({args})", vector_type(self.lang, n))
    }

    /// A level-0 sample of the texture at `coords` (and `layer`, for arrays).
    fn sample(&self, coords: &str, layer: Option<&str>) -> String {
        match (self.lang, layer) {
            (ShaderLang::Glsl, None) => format!("textureLod({TEXTURE}, {coords}, 0.0)"),
            (ShaderLang::Glsl, Some(l)) => {
                format!("textureLod({TEXTURE}, vec3({coords}, {l}), 0.0)")
            }
            (ShaderLang::Hlsl, None) => format!("{TEXTURE}.SampleLevel({SAMPLER}, {coords}, 0.0)"),
            (ShaderLang::Hlsl, Some(l)) => {
                format!("{TEXTURE}.SampleLevel({SAMPLER}, float3({coords}, {l}), 0.0)")
            }
            (ShaderLang::Wgsl, None) => {
                format!("textureSampleLevel({TEXTURE}, {SAMPLER}, {coords}, 0.0)")
            }
            (ShaderLang::Wgsl, Some(l)) => {
                format!("textureSampleLevel({TEXTURE}, {SAMPLER}, {coords}, i32({l}), 0.0)")
            }
        }
    }

    /// `value` divided by the scale, if any.
    fn unscaled(&self, value: String) -> String {
        match self.scale {
            Some(s) => format!("{value} / {}", float_literal(s)),
            None => value,
        }
    }

    /// The axis parameter declarations of the functions.
    fn axis_params(&self) -> Vec<String> {
        self.params
            .iter()
            .map(|p| match self.lang {
                ShaderLang::Wgsl => format!("{p}: f32"),
                ShaderLang::Glsl => format!("{GLSL_PRECISION} float {p}"),
                ShaderLang::Hlsl => format!("float {p}"),
            })
            .collect()
    }

    /// The texture (and sampler) parameter declarations of a function sampling `storage`.
    fn handles(&self, storage: Storage) -> String {
        match (self.lang, storage) {
            (ShaderLang::Glsl, Storage::Texture2d) => {
                format!("{GLSL_PRECISION} sampler2D {TEXTURE}")
            }
            (ShaderLang::Glsl, Storage::Texture3d) => {
                format!("{GLSL_PRECISION} sampler3D {TEXTURE}")
            }
            (ShaderLang::Glsl, Storage::Array) => {
                format!("{GLSL_PRECISION} sampler2DArray {TEXTURE}")
            }
            (ShaderLang::Hlsl, Storage::Texture2d) => {
                format!("Texture2D<float4> {TEXTURE}, SamplerState {SAMPLER}")
            }
            (ShaderLang::Hlsl, Storage::Texture3d) => {
                format!("Texture3D<float4> {TEXTURE}, SamplerState {SAMPLER}")
            }
            (ShaderLang::Hlsl, Storage::Array) => {
                format!("Texture2DArray<float4> {TEXTURE}, SamplerState {SAMPLER}")
            }
            (ShaderLang::Wgsl, Storage::Texture2d) => {
                format!("{TEXTURE}: texture_2d<f32>, {SAMPLER}: sampler")
            }
            (ShaderLang::Wgsl, Storage::Texture3d) => {
                format!("{TEXTURE}: texture_3d<f32>, {SAMPLER}: sampler")
            }
            (ShaderLang::Wgsl, Storage::Array) => {
                format!("{TEXTURE}: texture_2d_array<f32>, {SAMPLER}: sampler")
            }
        }
    }

    /// The whole function.
    fn function(&self, name: &str, storage: Storage) -> String {
        let lut = self.lut;
        let nc = lut.channels.len();
        let ret = match self.lang {
            ShaderLang::Glsl => format!("{GLSL_PRECISION} {}", vector_type(self.lang, nc)),
            _ => vector_type(self.lang, nc),
        };
        let swizzle = &"rgba"[..nc];
        let axis_params = self.axis_params();
        let handles = self.handles(storage);
        let params = format!("{handles}, {}", axis_params.join(", "));
        let mut f = match self.lang {
            ShaderLang::Wgsl => format!("fn {name}({params}) -> {ret} {{\n"),
            _ => format!("{ret} {name}({params})\n{{\n"),
        };
        for (k, a) in lut.axes.iter().enumerate() {
            f.push_str(&self.coordinate(k, a));
        }
        match storage {
            Storage::Texture2d => {
                let v = if lut.axes.len() == 1 { "0.5" } else { "s1_" };
                let coords = self.vec(2, &format!("s0_, {v}"));
                let value = format!("{}.{swizzle}", self.sample(&coords, None));
                let _ = writeln!(f, "    return {};", self.unscaled(value));
            }
            Storage::Texture3d => {
                let coords = self.vec(3, "s0_, s1_, s2_");
                let value = format!("{}.{swizzle}", self.sample(&coords, None));
                let _ = writeln!(f, "    return {};", self.unscaled(value));
            }
            Storage::Array => {
                let n = lut.dim(2);
                // the slice position, clamped as clamp-to-edge does, and its two layers
                f.push_str(&self.local(
                    "p_",
                    &format!(
                        "clamp(s2_ * {} - 0.5, 0.0, {})",
                        float_literal(n as f64),
                        float_literal((n - 1) as f64)
                    ),
                ));
                f.push_str(&self.local("l0_", "floor(p_)"));
                f.push_str(&self.local("l1_", "ceil(p_)"));
                let uv = self.vec(2, "s0_, s1_");
                let a = self.sample(&uv, Some("l0_"));
                let b = self.sample(&uv, Some("l1_"));
                let lerp = match self.lang {
                    ShaderLang::Hlsl => "lerp",
                    _ => "mix",
                };
                let value = format!("{lerp}({a}.{swizzle}, {b}.{swizzle}, p_ - l0_)");
                let _ = writeln!(f, "    return {};", self.unscaled(value));
            }
        }
        f.push_str("}\n");
        f
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::{Channel, Quantity};
    use crate::model::RoughnessQuantity;

    fn lut(axes: Vec<Axis>, nc: usize) -> Lut {
        let n: usize = axes.iter().map(|a| a.size).product();
        Lut {
            axes,
            channels: (0..nc)
                .map(|c| Channel {
                    name: format!("c{c}"),
                    meaning: "test".into(),
                })
                .collect(),
            data: (0..n * nc).map(|i| i as f32).collect(),
            error_estimate: vec![0.0; nc],
            evaluations: 0,
        }
    }

    fn axis(name: &str, size: usize, range: [f64; 2], convention: Convention) -> Axis {
        Axis {
            name: name.into(),
            quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
            size,
            range,
            convention,
            warp: Default::default(),
            clamp: None,
        }
    }

    #[test]
    fn coordinates_follow_the_conventions() {
        let t = lut(
            vec![
                axis("a", 4, [0.0, 1.0], Convention::Centers),
                axis("b", 5, [0.5, 1.0], Convention::Endpoints),
            ],
            1,
        );
        assert_eq!(texture_coordinates(&t, &[0.25, 0.5]), [0.25, 0.1]);
        assert_eq!(texture_coordinates(&t, &[-1.0, 2.0]), [0.0, 0.9]);
        let t = lut(vec![axis("a", 1, [0.5, 0.5], Convention::Centers)], 1);
        assert_eq!(texture_coordinates(&t, &[7.0]), [0.5]);
    }

    #[test]
    fn names_and_literals() {
        assert_eq!(lookup_function_name("dfg-ms"), "dfg_ms_lookup");
        assert_eq!(lookup_function_name("2d"), "lut_2d_lookup");
        assert_eq!(float_literal(1.0), "1.0");
        assert_eq!(float_literal(-0.5), "(-0.5)");
        assert_eq!(float_literal(1e-8), "1e-8");
        let t = lut(
            vec![
                axis("__n·v__", 2, [0.0, 1.0], Convention::Centers),
                axis("lut", 2, [0.0, 1.0], Convention::Centers),
                axis("9", 2, [0.0, 1.0], Convention::Centers),
            ],
            1,
        );
        assert_eq!(parameter_names(&t), ["n_v", "lut_axis1", "x_9"]);
    }

    #[test]
    fn too_many_channels_is_an_error() {
        let t = lut(vec![axis("a", 2, [0.0, 1.0], Convention::Centers)], 5);
        let s = ShaderSnippet {
            lang: ShaderLang::Glsl,
            table_name: "t".into(),
        };
        assert!(matches!(s.encode(&t, &[]), Err(EncodeError::Shape { .. })));
    }
}
