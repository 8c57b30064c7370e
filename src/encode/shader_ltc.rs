//! The area-light part of an `ltc` table's shader snippet (GLSL, HLSL, WGSL): what a shader
//! needs beyond the lookup to shade with a polygonal light from the table's texels.
//!
//! Heitz, Dupuy, Hill & Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
//! Transformed Cosines" (ACM TOG 35(4)): in the frame with the normal +z and the view in
//! the xz-plane at positive x, the integral of the LTC over a polygon `P` is the clamped
//! cosine's integral over `M⁻¹P` (their eq. 3), which Lambert's formula gives edge by edge
//! once `M⁻¹P` is clipped to the upper hemisphere (their §5.2; Arvo 1995, eq. 5):
//! `∫_P D = (1/2π) Σᵢ θᵢ (uᵢ × uᵢ₊₁)_z / |uᵢ × uᵢ₊₁|`, `θᵢ = ∠(uᵢ, uᵢ₊₁)`. The same sum in
//! f64 is [`crate::kernels::ltc_polygon::ltc_polygon_integral`].
//!
//! Functions, `P` the table's lower-case identifier (the lookup is `P_lookup`):
//! * with the four matrix channels: `P_ltc_theta_sin(x)` (`θ/sin θ` of `x = cos θ`),
//!   `P_ltc_edge(a, b)` (the vector `θ·(a × b)/|a × b|` of one edge between unit vectors),
//!   `P_ltc_unit`, `P_ltc_horizon` (where a segment crosses
//!   z = 0), `P_ltc_polygon(minv, n, v, pos, p0, p1, p2, p3)` (`∫_P D` of the LTC `minv`
//!   over the quad `p0…p3`, world space; a triangle repeats its first vertex as `p3`),
//!   and `P_ltc_minv(texture, [sampler,] axes…)` (M⁻¹ rebuilt from the lookup's texel);
//! * with `norm` and `fresnel`: `P_schlick_weight(texture, [sampler,] axes…, f0, f90)` =
//!   `f0·norm + (f90 − f0)·fresnel`.
//!
//! The shaded specular is `P_schlick_weight(…) · max(P_ltc_polygon(…), 0)` (one-sided;
//! `abs` for a two-sided light).
//!
//! **The edge integral in f32.** Each edge contributes `θ/sin θ · (a × b)` for unit `a`,
//! `b` with `x = a·b = cos θ`; the snippet computes `θ/sin θ = acos(x)/√(1 − x²)` to a few
//! f32 ulps over all of [−1, 1] with arithmetic and square roots only
//! (`P_ltc_theta_sin`), because the shading languages promise little of `acos` (Vulkan
//! and WebGPU give it the error of `atan2(√(1 − x²), x)`, up to 4096 ulps, and
//! `1 − x·x` cancels near x = ±1; measured on SwiftShader the textbook
//! `acos(x)·inversesqrt(1 − x²)` is off by up to 4·10⁻⁵ of the integral, tests/gpu_path.rs):
//! * for `|x| = cos θₐ`, halve the angle: `φ = θₐ/2`, `cos φ = c = √((1 + |x|)/2)`,
//!   `1 − c = ((1 − |x|)/2)/(1 + c)` (no cancellation; `1 − |x|` is exact for `|x| ≥ ½`,
//!   Sterbenz), and `θₐ/sin θₐ = (φ/sin φ)/cos φ`;
//! * `φ/sin φ = acos(1 − y)/√(2y − y²) = Σₖ 2ᵏ(k!)²/(2k + 1)! yᵏ` (its Taylor series at
//!   `y = 1 − cos φ = 0`, radius 2), summed to k = 9 for `y ≤ 1 − √½ = 0.293`: the terms
//!   left out are below 1.5·10⁻⁹ relative;
//! * for x < 0, `θ = π − θₐ` and `θ/sin θ = π/sin θₐ − θₐ/sin θₐ` with
//!   `sin θₐ = √((1 − x)(1 + x))` (`1 + x` exact for `x ≤ −½`). Towards x = −1 (an edge
//!   spanning half a great circle, seen through the shading point) the ratio grows without
//!   bound while `a × b` goes to 0; the product stays finite because the square root's
//!   argument is kept ≥ 10⁻³⁰.
//!
//! **Clipping.** Exact: the transformed polygon is clipped to z ≥ 0 as Sutherland &
//! Hodgman (1974) clip, streamed edge by edge (an exit point is joined along the horizon to
//! the next entry point, the last exit to the first entry). The `sphere` channel of Heitz
//! & Hill 2017 (a sphere with the polygon's vector form factor, clipped instead) is an
//! approximation and is not used.

use crate::lut::Lut;
use std::fmt::Write as _;

/// The snippet's language, as this module writes it.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Lang {
    Glsl,
    Hlsl,
    Wgsl,
}

/// What the area-light functions need from the lookup snippet.
pub(crate) struct Context<'a> {
    pub lang: Lang,
    /// The function-name prefix (the lookup is `{prefix}_lookup`).
    pub prefix: String,
    /// The texture (and sampler) parameter declarations of the lookup.
    pub handles: String,
    /// The same as arguments: `lut` or `lut, lut_sampler`.
    pub handle_args: String,
    /// The axis parameter declarations and names, in the lookup's order.
    pub axis_params: Vec<String>,
    pub axis_args: Vec<String>,
    pub lut: &'a Lut,
}

fn channel(lut: &Lut, name: &str) -> Option<usize> {
    lut.channels.iter().position(|c| c.name == name)
}

const COMPONENTS: [&str; 4] = ["r", "g", "b", "a"];

/// The `(m00, m20, m02, m22)` components of the lookup's texel, when the table has all four.
fn matrix_components(lut: &Lut) -> Option<[&'static str; 4]> {
    let mut out = [""; 4];
    for (o, name) in out.iter_mut().zip(["m00", "m20", "m02", "m22"]) {
        *o = COMPONENTS[channel(lut, name)?];
    }
    Some(out)
}

/// The `(norm, fresnel)` components, when the table has both.
fn schlick_components(lut: &Lut) -> Option<[&'static str; 2]> {
    Some([
        COMPONENTS[channel(lut, "norm")?],
        COMPONENTS[channel(lut, "fresnel")?],
    ])
}

/// Whether the table gets area-light functions (an `ltc` table with the matrix or the
/// norm and Fresnel channels, in a 2D texture).
pub(crate) fn applies(lut: &Lut, kind: Option<&str>) -> bool {
    kind == Some("ltc")
        && lut.axes.len() == 2
        && lut.channels.len() <= 4
        && (matrix_components(lut).is_some() || schlick_components(lut).is_some())
}

/// The comment lines (without markers) describing the area-light functions.
pub(crate) fn documentation(c: &Context) -> Vec<String> {
    let p = &c.prefix;
    let args = c.axis_args.join(", ");
    let handles = &c.handle_args;
    let mut d = vec![
        String::new(),
        "Area lights (LTC, Heitz, Dupuy, Hill & Neubelt 2016):".into(),
    ];
    if matrix_components(c.lut).is_some() {
        d.push(format!(
            "  {p}_ltc_minv({handles}, {args}) rebuilds the LTC's inverse matrix from the texel: \
             M^-1 / M^-1[1][1] = [[m00, 0, m02], [0, 1, 0], [m20, 0, m22]] (rows), in the frame with the \
             normal +z and the view in the xz-plane at positive x; its scale does not matter."
        ));
        d.push(format!(
            "  {p}_ltc_polygon(minv, n, v, pos, p0, p1, p2, p3) returns the LTC's integral over the \
             polygon light p0..p3 (world-space vertices; a triangle repeats p0 as p3) seen from the \
             shading point pos with unit normal n and unit view direction v (towards the eye): the \
             vertices are taken to the frame (t1 = the normalized part of v orthogonal to n, t2 = n x t1, \
             n; any tangent when v = n), multiplied by minv, clipped to the horizon exactly \
             (Sutherland-Hodgman, one edge at a time) and summed with Lambert's edge formula, \
             (1/2pi) sum theta_i (u_i x u_i+1).z / |u_i x u_i+1| with theta_i/sin(theta_i) = acos(x)/sqrt(1 - x^2) \
             computed to a few f32 ulps over [-1, 1] without acos ({p}_ltc_theta_sin: a half angle and a series; \
             the shading languages allow acos errors of thousands of ulps). It is \
             positive for vertices counterclockwise as seen from pos and negative for the other winding: \
             take max(., 0) for a one-sided light, abs(.) for a two-sided one. The table's sphere channel \
             (Heitz & Hill 2017's form-factor sphere, an approximation) is not needed."
        ));
        d.push(
            "  Both are evaluated at cos_theta_v = dot(n, v) and the surface's roughness, in the axes' \
             quantities above."
                .into(),
        );
    }
    if schlick_components(c.lut).is_some() {
        d.push(format!(
            "  {p}_schlick_weight({handles}, {args}, f0, f90) returns f0 * norm + (f90 - f0) * fresnel \
             (Schlick's Fresnel over the BRDF's lobe; f90 = 1 for Schlick's own)."
        ));
    }
    d.push(
        "  Specular radiance of a light of uniform radiance L: L * schlick_weight * max(ltc_polygon(ltc_minv(...), \
         n, v, pos, p0, p1, p2, p3), 0), with ltc_minv from the table holding m00, m20, m02, m22 and \
         schlick_weight from the one holding norm and fresnel (the same axes: pass the same arguments)."
            .into(),
    );
    d
}

/// `φ/sin φ = Σₖ 2ᵏ(k!)²/(2k + 1)! yᵏ`, `y = 1 − cos φ`, to k = 9, in Horner form (module doc).
const SERIES: &str = "1.0 + y * (0.333333343 + y * (0.13333334 + y * (0.0571428575 + y * (0.0253968257 \
     + y * (0.0115440115 + y * (0.00532800518 + y * (0.0024864024 + y * (0.00117007177 + y * 0.0005542445))))))))";

/// The functions (after the lookup function).
pub(crate) fn code(c: &Context) -> String {
    let mut out = String::new();
    if let Some(m) = matrix_components(c.lut) {
        out.push_str(&polygon_code(c));
        out.push('\n');
        out.push_str(&minv_code(c, m));
    }
    if let Some(s) = schlick_components(c.lut) {
        out.push('\n');
        out.push_str(&schlick_code(c, s));
    }
    out
}

/// The per-edge statements, the same text in the three languages (the locals are declared
/// before): the part of edge `a → b` above the horizon, and the horizon arcs.
fn edge_block(p: &str, a: &str, b: &str) -> String {
    format!(
        "    if ({a}.z > 0.0 && {b}.z > 0.0) {{\n\
         \x20       sum += {p}_ltc_edge({a}, {b}).z;\n\
         \x20   }}\n\
         \x20   if ({a}.z > 0.0 && !({b}.z > 0.0)) {{\n\
         \x20       x = {p}_ltc_horizon({a}, {b});\n\
         \x20       sum += {p}_ltc_edge({a}, x).z;\n\
         \x20       exit_point = x;\n\
         \x20       has_exit = true;\n\
         \x20   }}\n\
         \x20   if (!({a}.z > 0.0) && {b}.z > 0.0) {{\n\
         \x20       x = {p}_ltc_horizon({a}, {b});\n\
         \x20       sum += {p}_ltc_edge(x, {b}).z;\n\
         \x20       if (has_exit) {{\n\
         \x20           sum += {p}_ltc_edge(exit_point, x).z;\n\
         \x20           has_exit = false;\n\
         \x20       }} else {{\n\
         \x20           first_entry = x;\n\
         \x20           has_first = true;\n\
         \x20       }}\n\
         \x20   }}\n"
    )
}

fn polygon_code(c: &Context) -> String {
    let p = &c.prefix;
    let mut f = String::new();
    let (vec3, float, hp) = match c.lang {
        Lang::Glsl => ("vec3", "float", "highp "),
        Lang::Hlsl => ("float3", "float", ""),
        Lang::Wgsl => ("vec3<f32>", "f32", ""),
    };
    let rsqrt = match c.lang {
        Lang::Glsl => "inversesqrt",
        Lang::Hlsl => "rsqrt",
        Lang::Wgsl => "inverseSqrt",
    };
    // signatures
    let sig = |name: &str, params: &[(&str, &str)], ret: &str| -> String {
        match c.lang {
            Lang::Wgsl => {
                let ps: Vec<String> = params.iter().map(|(n, t)| format!("{n}: {t}")).collect();
                format!("fn {name}({}) -> {ret} {{\n", ps.join(", "))
            }
            _ => {
                let ps: Vec<String> = params.iter().map(|(n, t)| format!("{hp}{t} {n}")).collect();
                format!("{hp}{ret} {name}({})\n{{\n", ps.join(", "))
            }
        }
    };
    let let_ = |name: &str, ty: &str, expr: &str| -> String {
        match c.lang {
            Lang::Wgsl => format!("    let {name} = {expr};\n"),
            _ => format!("    {hp}{ty} {name} = {expr};\n"),
        }
    };
    let var_ = |name: &str, ty: &str, expr: &str| -> String {
        match c.lang {
            Lang::Wgsl => format!("    var {name}: {ty} = {expr};\n"),
            Lang::Glsl if ty == "bool" => format!("    bool {name} = {expr};\n"),
            _ => format!("    {hp}{ty} {name} = {expr};\n"),
        }
    };
    // θ/sin θ of x = cos θ, then the edge vector
    f.push_str(&sig(&format!("{p}_ltc_theta_sin"), &[("x", float)], float));
    f.push_str(&let_("a", float, "abs(x)"));
    f.push_str(&let_("c", float, "sqrt(0.5 + 0.5 * a)"));
    f.push_str(&let_("y", float, "(0.5 - 0.5 * a) / (1.0 + c)"));
    f.push_str(&var_("g", float, &format!("({SERIES}) / c")));
    let _ = write!(
        f,
        "    if (x < 0.0) {{\n        g = 3.14159274 * {rsqrt}(max((1.0 - x) * (1.0 + x), 1e-30)) - g;\n    }}\n    return g;\n}}\n\n"
    );
    f.push_str(&sig(
        &format!("{p}_ltc_edge"),
        &[("a", vec3), ("b", vec3)],
        vec3,
    ));
    let _ = write!(
        f,
        "    return {p}_ltc_theta_sin(clamp(dot(a, b), -1.0, 1.0)) * cross(a, b);\n}}\n\n"
    );
    // normalization that leaves a zero vector at zero
    f.push_str(&sig(&format!("{p}_ltc_unit"), &[("v", vec3)], vec3));
    let _ = writeln!(f, "    return v * {rsqrt}(max(dot(v, v), 1e-30));\n}}\n");
    // the horizon crossing of a segment whose ends lie on either side of z = 0
    f.push_str(&sig(
        &format!("{p}_ltc_horizon"),
        &[("a", vec3), ("b", vec3)],
        vec3,
    ));
    let _ = writeln!(
        f,
        "    return {p}_ltc_unit({vec3}(a.xy + (b.xy - a.xy) * (a.z / (a.z - b.z)), 0.0));\n}}\n"
    );
    // the polygon
    let mat3 = match c.lang {
        Lang::Glsl => "mat3",
        Lang::Hlsl => "float3x3",
        Lang::Wgsl => "mat3x3<f32>",
    };
    f.push_str(&sig(
        &format!("{p}_ltc_polygon"),
        &[
            ("minv", mat3),
            ("n", vec3),
            ("v", vec3),
            ("pos", vec3),
            ("p0", vec3),
            ("p1", vec3),
            ("p2", vec3),
            ("p3", vec3),
        ],
        float,
    ));
    f.push_str(&var_("t1", vec3, "v - n * dot(n, v)"));
    f.push_str(&let_("l", float, "dot(t1, t1)"));
    let sign = match c.lang {
        Lang::Wgsl => "select(-1.0, 1.0, n.z >= 0.0)",
        _ => "(n.z >= 0.0 ? 1.0 : -1.0)",
    };
    f.push_str(&format!(
        "    if (l > 1e-12) {{\n        t1 = t1 * {rsqrt}(l);\n    }} else {{\n        // any tangent (Duff et al. 2017, \"Building an Orthonormal Basis, Revisited\")\n"
    ));
    let inner = |name: &str, ty: &str, expr: &str| format!("    {}", let_(name, ty, expr));
    f.push_str(&inner("s", float, sign));
    f.push_str(&inner("k", float, "-1.0 / (s + n.z)"));
    let _ = writeln!(
        f,
        "        t1 = {vec3}(1.0 + s * n.x * n.x * k, s * n.x * n.y * k, -s * n.x);\n    }}"
    );
    f.push_str(&let_("t2", vec3, "cross(n, t1)"));
    for i in 0..4 {
        let local = format!("{vec3}(dot(p{i} - pos, t1), dot(p{i} - pos, t2), dot(p{i} - pos, n))");
        let q = match c.lang {
            Lang::Hlsl => format!("mul(minv, {local})"),
            _ => format!("minv * {local}"),
        };
        f.push_str(&let_(&format!("u{i}"), vec3, &format!("{p}_ltc_unit({q})")));
    }
    let zero3 = match c.lang {
        Lang::Wgsl => "vec3<f32>(0.0)",
        Lang::Glsl => "vec3(0.0)",
        Lang::Hlsl => "float3(0.0, 0.0, 0.0)",
    };
    f.push_str(&var_("sum", float, "0.0"));
    f.push_str(&var_("x", vec3, zero3));
    f.push_str(&var_("exit_point", vec3, zero3));
    f.push_str(&var_("first_entry", vec3, zero3));
    f.push_str(&var_("has_exit", "bool", "false"));
    f.push_str(&var_("has_first", "bool", "false"));
    for (a, b) in [("u0", "u1"), ("u1", "u2"), ("u2", "u3"), ("u3", "u0")] {
        f.push_str(&edge_block(p, a, b));
    }
    let _ = write!(
        f,
        "    if (has_exit && has_first) {{\n        sum += {p}_ltc_edge(exit_point, first_entry).z;\n    }}\n    return sum * 0.15915494;\n}}\n"
    );
    f
}

/// The header of a function taking the lookup's texture and axes, and more parameters.
fn table_function(c: &Context, name: &str, ret: &str, extra: &[(&str, &str)]) -> String {
    let mut params = vec![c.handles.clone()];
    params.extend(c.axis_params.iter().cloned());
    for (n, t) in extra {
        params.push(match c.lang {
            Lang::Wgsl => format!("{n}: {t}"),
            Lang::Glsl => format!("highp {t} {n}"),
            Lang::Hlsl => format!("{t} {n}"),
        });
    }
    match c.lang {
        Lang::Wgsl => format!("fn {name}({}) -> {ret} {{\n", params.join(", ")),
        Lang::Glsl => format!("highp {ret} {name}({})\n{{\n", params.join(", ")),
        Lang::Hlsl => format!("{ret} {name}({})\n{{\n", params.join(", ")),
    }
}

fn texel(c: &Context) -> String {
    let nc = c.lut.channels.len();
    let ty = match (c.lang, nc) {
        (Lang::Wgsl, _) => String::new(),
        (Lang::Glsl, 1) => "highp float ".into(),
        (Lang::Glsl, n) => format!("highp vec{n} "),
        (Lang::Hlsl, 1) => "float ".into(),
        (Lang::Hlsl, n) => format!("float{n} "),
    };
    let decl = if c.lang == Lang::Wgsl { "let " } else { "" };
    format!(
        "    {decl}{ty}t = {}_lookup({}, {});\n",
        c.prefix,
        c.handle_args,
        c.axis_args.join(", ")
    )
}

fn minv_code(c: &Context, m: [&str; 4]) -> String {
    let [m00, m20, m02, m22] = m;
    let (ret, body) = match c.lang {
        // column-major constructors: columns (m00, 0, m20), (0, 1, 0), (m02, 0, m22)
        Lang::Glsl => (
            "mat3",
            format!("mat3(vec3(t.{m00}, 0.0, t.{m20}), vec3(0.0, 1.0, 0.0), vec3(t.{m02}, 0.0, t.{m22}))"),
        ),
        Lang::Wgsl => (
            "mat3x3<f32>",
            format!(
                "mat3x3<f32>(vec3<f32>(t.{m00}, 0.0, t.{m20}), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(t.{m02}, 0.0, t.{m22}))"
            ),
        ),
        // HLSL's constructor takes rows
        Lang::Hlsl => (
            "float3x3",
            format!("float3x3(t.{m00}, 0.0, t.{m02}, 0.0, 1.0, 0.0, t.{m20}, 0.0, t.{m22})"),
        ),
    };
    let mut f = table_function(c, &format!("{}_ltc_minv", c.prefix), ret, &[]);
    f.push_str(&texel(c));
    let _ = writeln!(f, "    return {body};\n}}");
    f
}

fn schlick_code(c: &Context, s: [&str; 2]) -> String {
    let [norm, fresnel] = s;
    let vec3 = match c.lang {
        Lang::Glsl => "vec3",
        Lang::Hlsl => "float3",
        Lang::Wgsl => "vec3<f32>",
    };
    let mut f = table_function(
        c,
        &format!("{}_schlick_weight", c.prefix),
        vec3,
        &[("f0", vec3), ("f90", vec3)],
    );
    f.push_str(&texel(c));
    let _ = writeln!(
        f,
        "    return f0 * t.{norm} + (f90 - f0) * t.{fresnel};\n}}"
    );
    f
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lut::{Axis, Channel, Convention, Quantity};
    use crate::model::RoughnessQuantity;

    /// The literals of [`SERIES`], in order.
    fn coefficients() -> Vec<f64> {
        SERIES
            .split(|c: char| "()*+ ".contains(c))
            .filter_map(|t| t.parse::<f64>().ok())
            .collect()
    }

    /// The series' literals are `2ᵏ(k!)²/(2k + 1)!` rounded to f32, and the snippet's
    /// `θ/sin θ` (its formula evaluated in f64 with those literals) is within 2·10⁻⁸ of
    /// `acos(x)/√(1 − x²)` on [−1, 1): the truncation leaves < 1.5·10⁻⁹ (module doc), and
    /// each literal is off by at most half an f32 ulp, 3·10⁻⁸ relative, of a term ≤ 0.1 past
    /// the first (k ≥ 1: `c₁y ≤ ⅓·0.293`), so the ten add < 10⁻⁸.
    #[test]
    fn theta_over_sin_theta_is_accurate() {
        let c = coefficients();
        assert_eq!(c.len(), 10);
        let mut exact = 1.0f64;
        for (k, &ck) in c.iter().enumerate() {
            if k > 0 {
                // c_k = c_{k−1}·2k²/(2k(2k + 1)) = c_{k−1}·k/(2k + 1)
                exact *= k as f64 / (2 * k + 1) as f64;
            }
            assert_eq!(ck as f32, exact as f32, "coefficient {k}");
        }
        let theta_sin = |x: f64| {
            let a = x.abs();
            let cs = (0.5 + 0.5 * a).sqrt();
            let y = (0.5 - 0.5 * a) / (1.0 + cs);
            let g = c.iter().rev().fold(0.0, |s, &ck| s * y + ck) / cs;
            if x < 0.0 {
                std::f64::consts::PI / ((1.0 - x) * (1.0 + x)).sqrt() - g
            } else {
                g
            }
        };
        for i in 0..=2000 {
            let x = -0.9999 + 1.9999 * i as f64 / 2000.0;
            let want = if x == 1.0 {
                1.0
            } else {
                x.acos() / (1.0 - x * x).sqrt()
            };
            let got = theta_sin(x);
            assert!((got / want - 1.0).abs() < 2e-8, "x = {x}: {got} vs {want}");
        }
    }

    fn lut(channels: &[&str]) -> Lut {
        let axis = |name: &str| Axis {
            name: name.into(),
            quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
            size: 2,
            range: [0.0, 1.0],
            convention: Convention::Endpoints,
            warp: Default::default(),
            clamp: None,
        };
        Lut {
            axes: vec![axis("roughness"), axis("cos_theta_v")],
            channels: channels
                .iter()
                .map(|c| Channel {
                    name: c.to_string(),
                    meaning: String::new(),
                })
                .collect(),
            data: vec![0.0; 4 * channels.len()],
            error_estimate: vec![0.0; channels.len()],
            evaluations: 0,
        }
    }

    #[test]
    fn only_ltc_tables_with_the_channels_get_the_functions() {
        let matrix = lut(&["m00", "m20", "m02", "m22"]);
        let schlick = lut(&["norm", "fresnel", "zero", "sphere"]);
        assert!(applies(&matrix, Some("ltc")));
        assert!(applies(&schlick, Some("ltc")));
        assert!(!applies(&matrix, Some("dfg")));
        assert!(!applies(&matrix, None));
        assert!(!applies(&lut(&["sphere"]), Some("ltc")));
        assert!(!applies(&lut(&["m00", "norm"]), Some("ltc")));
        assert_eq!(matrix_components(&matrix), Some(["r", "g", "b", "a"]));
        assert_eq!(
            matrix_components(&lut(&["m22", "m02", "m20", "m00"])),
            Some(["a", "b", "g", "r"])
        );
        assert_eq!(schlick_components(&schlick), Some(["r", "g"]));
    }
}
