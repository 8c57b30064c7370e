//! The JSON sidecar written next to every texture (schema `brdfbake.lut/1`, documented in
//! `docs/metadata.md`): everything an engine needs to sample the texture without guessing.

use crate::lut::{Axis, Convention, Lut, Quantity, Warp};
use crate::preset::PresetTable;
use crate::table::{DfgLayout, Storage, TableKind, TableSpec};
use serde_json::{json, Value};
use sha2::{Digest, Sha256};

/// The metadata schema identifier.
pub const SCHEMA: &str = "brdfbake.lut/1";
/// The sidecar `table.kind` of the tables `measured --out` writes (no preset table behind
/// them, nothing to recompute them from).
pub const MEASURED_TABLE_KIND: &str = "measured-albedo";
/// brdfbake's version, recorded in every output and in the input hash.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The canonical description of a table's inputs: what is hashed. Two tables with equal
/// inputs produce byte-identical outputs.
pub fn inputs(table: &PresetTable) -> Value {
    let spec = &table.spec;
    let m = &spec.model;
    let mut v = json!({
        "kind": spec.kind.name(),
        "model": {
            "ndf": m.ndf.map(|n| n.name()),
            "masking": m.masking.name(),
            "fresnel": m.fresnel,
            "diffuse": m.diffuse_weight,
        },
        "axes": spec.axes.iter().map(|a| {
            let mut v = json!({
                "name": a.name,
                "quantity": quantity_name(a),
                "size": a.size,
                "range": a.range,
                "convention": a.convention.name(),
            });
            // (only when set, so that linear unclamped axes keep their hash)
            if a.warp != Warp::Linear {
                v["warp"] = json!(a.warp.name());
            }
            if let Some(c) = a.clamp {
                v["clamp"] = json!(c);
            }
            v
        }).collect::<Vec<_>>(),
        "layout": spec.dfg_layout,
        "cloth": spec.cloth,
        "storage": spec.storage,
        "tolerance": spec.tolerance,
        "scale": table.scale,
        "layout_3d": table.layout_3d,
    });
    if let Some(c) = &m.classic {
        v["model"]["classic"] = json!(c);
    }
    // (only when not Lambert's, so that every other table keeps its hash)
    if m.diffuse_model != crate::model::DiffuseModel::Lambert {
        v["model"]["diffuse_model"] = json!(m.diffuse_model.name());
    }
    // (only when set, so that tables without it keep their hash)
    if let Some(a) = table.accept_error_estimate {
        v["accept_error_estimate"] = json!(a);
    }
    if let Some(e) = table.engine {
        v["engine"] = json!(e.name());
    }
    // (only when set, so that tables without it keep their hash)
    if let Some(f) = &table.fit {
        v["fit"] = fit_request_json(f);
    }
    if let Some(a) = spec.cloth_alpha_min {
        v["cloth_alpha_min"] = json!(a);
    }
    if let Some(c) = &spec.ltc_channels {
        v["ltc_channels"] = json!(c.iter().map(|c| c.name()).collect::<Vec<_>>());
    }
    if let Some(o) = &table.axis_order {
        v["axis_order"] = json!(o
            .iter()
            .map(|&k| spec.axes[k].name.clone())
            .collect::<Vec<_>>());
    }
    if let Some(c) = &table.channels {
        let kind = crate::table::channels(spec);
        v["channels"] = json!(c.iter().map(|s| s.text(&kind)).collect::<Vec<_>>());
    }
    v
}

/// The `channels` sidecar field: per stored channel its index, name and meaning; with the
/// preset's `channels` set, also what it stores (the preset's entry), the computed channel it
/// is made from and the transform.
/// The sidecar's `axes` and `channels` sections as this version writes them for `table`:
/// functions of the table alone (coordinates and α recomputed from each axis' formula), so a
/// reader can check a sidecar against itself.
pub fn axes_and_channels(table: &PresetTable) -> (Value, Value) {
    let lut = Lut {
        axes: table.stored_axes(),
        channels: table.stored_channels(),
        data: Vec::new(),
        error_estimate: Vec::new(),
        evaluations: 0,
    };
    (json!(axes_json(&lut.axes)), channels_json(table, &lut))
}

fn channels_json(table: &PresetTable, lut: &Lut) -> Value {
    let Some(stored) = &table.channels else {
        return json!(lut
            .channels
            .iter()
            .enumerate()
            .map(|(i, c)| json!({"index": i, "name": c.name, "meaning": c.meaning}))
            .collect::<Vec<_>>());
    };
    let kind = crate::table::channels(&table.spec);
    json!(lut
        .channels
        .iter()
        .zip(stored)
        .enumerate()
        .map(|(i, (c, s))| {
            json!({
                "index": i,
                "name": c.name,
                "meaning": c.meaning,
                "stores": s.text(&kind),
                "source": s.source().map(|k| kind[k].name.clone()),
                "transform": s.transform(),
            })
        })
        .collect::<Vec<_>>())
}

/// The one-line summary of the stored channels (`R = A, G = B, B = 0`), when `channels` is set.
pub fn channels_summary(table: &PresetTable) -> Option<String> {
    let stored = table.channels.as_ref()?;
    let kind = crate::table::channels(&table.spec);
    Some(
        stored
            .iter()
            .zip(crate::preset::COMPONENT_NAMES)
            .map(|(s, n)| format!("{n} = {}", s.text(&kind)))
            .collect::<Vec<_>>()
            .join(", "),
    )
}

/// `sha256:<hex>` of the canonical inputs and brdfbake's version.
pub fn input_hash(table: &PresetTable) -> String {
    let mut h = Sha256::new();
    h.update(b"brdfbake ");
    h.update(VERSION.as_bytes());
    h.update(b"\n");
    h.update(
        serde_json::to_string(&inputs(table))
            .expect("serializable")
            .as_bytes(),
    );
    let d = h.finalize();
    let hex: String = d.iter().map(|b| format!("{b:02x}")).collect();
    format!("sha256:{hex}")
}

/// A table's `fit` request as the preset spells it (`max_error` or `max_ops`, `weight`,
/// `emit`).
fn fit_request_json(f: &crate::fit::request::Request) -> Value {
    let mut o = match f.goal {
        crate::fit::request::Goal::MaxError(e) => json!({ "max_error": e }),
        crate::fit::request::Goal::MaxOps(n) => json!({ "max_ops": n }),
    };
    o["weight"] = json!(f.weight.name());
    o["emit"] = json!(f.emit);
    o
}

fn quantity_name(a: &Axis) -> String {
    match a.quantity {
        Quantity::Cosine => "cosine".into(),
        Quantity::Roughness(q) => format!("roughness:{}", q.name()),
        Quantity::Fresnel(q) => format!("fresnel:{}", q.name()),
        Quantity::Anisotropy => "anisotropy".into(),
        Quantity::FormFactor => "form-factor".into(),
    }
}

fn texture_axis(k: usize) -> &'static str {
    ["u", "v", "w (slice)"][k]
}

/// [`axis_json`] of every axis of a table; a critical-angle axis, whose texels sit at
/// other coordinates in every slice of the fresnel axis, lists its coordinates per fresnel
/// texel (`coordinates[f][i]`: texel i in fresnel texel f).
fn axes_json(axes: &[Axis]) -> Vec<Value> {
    axes.iter()
        .enumerate()
        .map(|(k, a)| {
            let mut v = axis_json(k, a);
            if a.warp.is_coupled() {
                let cs = crate::lut::critical_cosines(axes);
                let per = |f: &dyn Fn(usize, f64) -> f64| {
                    cs.iter()
                        .map(|&c| (0..a.size).map(|i| f(i, c)).collect::<Vec<_>>())
                        .collect::<Vec<_>>()
                };
                v["coordinates"] = json!(per(&|i, c| a.coord_at(i, c)));
                v["coordinates_index"] = json!("[fresnel texel][texel]: each fresnel texel's critical cosine c places this axis' texels");
                v["critical_cosines"] = json!(cs);
                if a.clamp.is_some() {
                    v["nominal_coordinates"] = json!(per(&|i, c| a.nominal_coord_at(i, c)));
                }
            }
            v
        })
        .collect()
}

pub(crate) fn axis_json(k: usize, a: &Axis) -> Value {
    let [lo, hi] = a.range;
    // what is uniform in the texels: x itself, or the warp's parameter p
    let linear = a.warp == Warp::Linear;
    let (pi, p) = if linear { ("x_i", "x") } else { ("p_i", "p") };
    let (mut texel, mut remap) = match a.convention {
        Convention::Centers => (
            format!("{pi} = {lo} + ({hi} - {lo}) * (i + 0.5) / {}", a.size),
            format!("t = ({p} - {lo}) / ({hi} - {lo}); sample at t directly (texel centres hold the values)"),
        ),
        Convention::Endpoints => (
            format!("{pi} = {lo} + ({hi} - {lo}) * i / ({} - 1)", a.size),
            format!(
                "t = ({p} - {lo}) / ({hi} - {lo}); sample at (0.5 + t * ({n} - 1)) / {n} (half-texel remap: the range ends are texel centres)",
                n = a.size
            ),
        ),
    };
    if !linear {
        let inverse = a.warp.inverse_formula().replace('p', "p_i");
        texel = format!("{texel}; x_i = {}", inverse.trim_start_matches("x = "));
        remap = format!("{} with x clamped to [0, 1]; {remap}", a.warp.formula());
    }
    if let Some([c0, c1]) = a.clamp {
        texel = format!("{texel}; the texel holds the value at clamp(x_i, {c0}, {c1})");
    }
    let mut v = json!({
        "name": a.name,
        "texture_axis": texture_axis(k),
        "quantity": quantity_name(a),
        "size": a.size,
        "range": a.range,
        "convention": a.convention.name(),
        "texel_coordinate": texel,
        "shader_texture_coordinate": remap,
        "coordinates": a.coords(),
    });
    if !linear {
        v["warp"] = json!({
            "name": a.warp.name(),
            "parameter": a.warp.formula(),
            "coordinate": a.warp.inverse_formula(),
        });
    }
    if let Some(c) = a.clamp {
        // `coordinates` are where the texels were evaluated; these, where they sit
        v["clamp"] = json!(c);
        v["nominal_coordinates"] =
            json!((0..a.size).map(|i| a.nominal_coord(i)).collect::<Vec<_>>());
    }
    if let Quantity::Roughness(q) = a.quantity {
        v["alpha_mapping"] = json!(q.mapping());
        v["alpha"] = json!((0..a.size)
            .map(|i| a.alpha(i).unwrap_or(f64::NAN))
            .collect::<Vec<_>>());
    }
    if let Quantity::Fresnel(q) = a.quantity {
        v["parameter_mapping"] = json!(q.mapping());
        v["parameter"] = json!(q.parameter_name());
        v["parameter_values"] = json!((0..a.size)
            .map(|i| a.fresnel_parameter(i).unwrap_or(f64::NAN))
            .collect::<Vec<_>>());
    }
    v
}

/// How a shader uses the channels.
pub fn reconstruction(spec: &TableSpec) -> &'static str {
    match spec.kind {
        TableKind::Ndf => "D(n.h) in the modern form: f = D G F / (4 (n.l)(n.v)). The lecture's Cook-Torrance D_CT = (pi/4) D.",
        TableKind::G1 => "G1(cos theta); Smith G2 separable = G1(v) G1(l), height-correlated = 1/(1/G1(v) + 1/G1(l) - 1).",
        TableKind::G2 => "G2(n.v, n.l) in f = D G2 F / (4 (n.l)(n.v)).",
        TableKind::Vgroove => "G(n.l, n.h, n.v) in Cook-Torrance's f_s = F D_CT G / (pi (n.l)(n.v)); use only where realizable = 1.",
        TableKind::Albedo => "E(mu): fraction of light reflected for a view at cos theta_v = mu under uniform white illumination; energy lost to single scattering is 1 - E.",
        TableKind::AlbedoAvg => "E_avg; Kulla-Conty multiple scattering lobe f_ms(mu_o, mu_i) = (1 - E(mu_o))(1 - E(mu_i)) / (pi (1 - E_avg)).",
        TableKind::Dfg => match spec.dfg_layout {
            Some(DfgLayout::Karis) => "specular = prefiltered_radiance * (F0 * A + B) (Karis 2013 split sum, Schlick Fresnel).",
            Some(DfgLayout::KarisF82) => "specular = prefiltered_radiance * (F0 * A + F90 * B - b * F82) for the F82-tint Fresnel F = F0 + (F90 - F0)(1 - v.h)^5 - b (v.h)(1 - v.h)^6 (Hoffman 2023; with F90 = 1 and the tint F82 at cos = 1/7: b = mix(F0, 1, (6/7)^5) (1 - F82) 7^7/6^6, as EEVEE's brdf_f82_tint_lut).",
            _ => "E = (1 - F0) * R + F0 * G = mix(R, G, F0); multiscatter energy compensation: specular *= 1 + F0 * (1 / G - 1); cloth: sheen = prefiltered * B (Filament).",
        },
        TableKind::KullaConty | TableKind::AlbedoFresnel | TableKind::DielectricBtdf => {
            crate::table::energy::reconstruction(spec)
        }
        TableKind::DielectricAlbedo | TableKind::DielectricAlbedoAvg => {
            crate::table::dielectric::reconstruction(spec)
        }
        TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => crate::table::schlick_weight::reconstruction(spec),
        TableKind::DielectricSchlick => crate::table::dielectric_schlick::reconstruction(spec),
        TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => {
            crate::table::classic::reconstruction(spec)
        }
        TableKind::Ltc => "area light (Heitz et al. 2016): in the frame with the normal +z and the view in the xz-plane, minv = mat3(vec3(m00, 0, m20), vec3(0, 1, 0), vec3(m02, 0, m22)) (columns; M^-1 up to scale, which the integral ignores); transform the light's vertices (relative to the shading point) by minv, clip the polygon to z > 0 and sum Lambert's edge terms: form factor = (1/2pi) sum_i acos(p_i.p_i+1) (p_i x p_i+1).z / |p_i x p_i+1| = int_P D; specular = light radiance * (F0 * norm + (F90 - F0) * fresnel) * form factor. The ltc section says where each channel is; the GLSL/HLSL/WGSL snippets implement it.",
        TableKind::LtcSphere => "a sphere or disk light (Heitz & Hill 2017): with the vector form factor F of the light transformed by M^-1 (the sum of the edge vectors / 2pi, unclipped), len = |F|, z = F.z / len: clipped form factor = len * table(z, len); EEVEE's ltc_diffuse_sphere_integral samples it at uv = (z * 0.5 + 0.5, len) on the endpoints grid.",
    }
}

/// The `model` object.
fn model_json(spec: &TableSpec) -> Value {
    if spec.kind.is_classic() {
        return crate::table::classic::model_json(spec);
    }
    let m = &spec.model;
    let ndf = m.ndf.map(|n| {
        json!({
            "name": n.name(),
            "formula": n.formula(),
            "source": n.source(),
            "lambda": if n.closed_form_lambda() { "closed form" } else { "derived numerically from D (Smith normalization, Heitz 2014), piecewise-Chebyshev to 1e-11" },
        })
    });
    let mut v = json!({
        "form": "modern: f = w_s D G F / (4 (n.l)(n.v)) + w_d / pi, with int D (n.h) dw_h = 1",
        "cook_torrance_form": "equivalent to the lecture's f_s = (1/pi) F D_CT G / ((n.l)(n.v)) with D_CT = (pi/4) D (its D carries a 1/4, its f_s a 1/pi)",
        "ndf": ndf,
        "masking": {"name": m.masking.name(), "formula": m.masking.formula(), "source": m.masking.source()},
        "fresnel": {"name": m.fresnel.name(), "formula": m.fresnel.formula(), "parameters": m.fresnel},
        "diffuse": {"name": if m.diffuse_weight > 0.0 { m.diffuse_model.name() } else { "none" }, "weight": m.diffuse_weight, "formula": m.diffuse_model.formula()},
    });
    if spec.kind == TableKind::AlbedoFresnel || spec.kind.is_dielectric() {
        let z = spec.axes.len() - 1;
        v["fresnel"] = json!({
            "name": "per slice, from the fresnel axis",
            "parameters": m.fresnel,
            "parameters_meaning": "the preset's model.fresnel: none (Schlick for an F0 axis, exact dielectric for an eta axis) or a conductor whose k is kept and eta replaced by the axis",
            "slices": (0..spec.axes[z].size).map(|k| {
                let f = if spec.kind == TableKind::AlbedoFresnel {
                    crate::table::energy::fresnel_of_slice(spec, k)
                } else {
                    crate::model::Fresnel::Dielectric { eta: crate::table::dielectric::eta_of_slice(spec, k) }
                };
                json!({"name": f.name(), "formula": f.formula(), "parameters": f})
            }).collect::<Vec<_>>(),
        });
    }
    if spec.kind.is_dielectric() {
        let g = if m.masking == crate::model::Masking::SmithHeightCorrelated {
            "G = 1/(1 + Lambda(v) + Lambda(l)) height-correlated Smith on both sides (as Cycles and pbrt-v4; Heitz 2014 derives B(1 + Lambda(v), 1 + Lambda(l)) for transmission)"
        } else {
            "G = G1(v) G1(l) separable Smith"
        };
        v["form"] = json!(format!("rough dielectric interface (Walter et al. 2007): f_r = D G F / (4 |n.l| |n.v|), f_t = |v.h| |l.h| / (|n.v| |n.l|) eta^2 (1 - F) D G / (v.h + eta l.h)^2, eta = eta_inside / eta_view_side, {g}"));
    }
    if spec.kind == TableKind::DielectricSchlick {
        let z = spec.axes.len() - 1;
        v["fresnel"] = json!({
            "name": "schlick, per slice: F0 = ((1 - eta)/(1 + eta))^2 of the fresnel axis' eta, weight s = (1 - cos theta_o)^5 on the less dense side (1 under total internal reflection); F0 and F90 are left to the shader (the channels are their weights)",
            "slices_eta": (0..spec.axes[z].size).map(|k| crate::table::dielectric::eta_of_slice(spec, k)).collect::<Vec<_>>(),
        });
        let g = if m.masking == crate::model::Masking::SmithHeightCorrelated {
            "G = 1/(1 + Lambda(v) + Lambda(l)) height-correlated Smith on both sides"
        } else {
            "G = G1(v) G1(l) separable Smith"
        };
        v["form"] = json!(format!("Schlick split sum of a rough dielectric interface (Walter et al. 2007 with Schlick's F): A = int D c/(n.v) (1 - s) G(v, l_r), B = int D c/(n.v) s G(v, l_r), T = int D c/(n.v) (1 - s) G(v, l_t) over micro-normals h (c = v.h), eta = eta_inside / eta_view_side, {g}"));
    }
    if spec.kind == TableKind::Dfg {
        v["split_sum"] = json!({
            "fresnel_weight": "Fc = (1 - v.h)^5 (Schlick); f is evaluated with F = 1",
            "layout": spec.dfg_layout,
        });
        if spec.cloth {
            v["cloth"] = json!({
                "ndf": {"name": "charlie", "formula": crate::model::NdfKind::Charlie.formula(), "source": crate::model::NdfKind::Charlie.source()},
                "visibility": crate::model::Masking::Ashikhmin.formula(),
                "alpha": "the same alpha as the specular channels (roughness axis mapping)",
            });
            if let Some(a) = spec.cloth_alpha_min {
                v["cloth"]["alpha"] = json!(format!(
                    "max(alpha, {a}): the specular channels' alpha (roughness axis mapping), floored at cloth_alpha_min"
                ));
                v["cloth"]["alpha_min"] = json!(a);
            }
        }
    }
    v
}

/// The full sidecar for a baked table. `files` maps format names to file names.
pub fn metadata(preset: &str, table: &PresetTable, lut: &Lut, files: &[(String, String)]) -> Value {
    metadata_with_fit(preset, table, lut, files, None)
}

/// [`metadata`], with the per-texel fit error of an `ltc` table (in the stored layout, as
/// `lut`; [`crate::table::bake_with_fit`]) in its `ltc.fit_error` section.
pub fn metadata_with_fit(
    preset: &str,
    table: &PresetTable,
    lut: &Lut,
    files: &[(String, String)],
    fit: Option<&Lut>,
) -> Value {
    let spec = &table.spec;
    let dims: Vec<usize> = lut.axes.iter().map(|a| a.size).collect();
    let (texel_type, rounding) = match spec.storage {
        Storage::F32 => (
            "f32",
            "round to nearest f32: relative 2^-24 (6e-8 for values <= 1)",
        ),
        Storage::F16 => (
            "f16",
            "round to nearest even f16: relative 2^-11 (4.9e-4 for values <= 1)",
        ),
        Storage::Unorm8 => (
            "unorm8",
            "8-bit unsigned normalized: code = round(value * scale * 255), ties to even, a sampler reads code / 255; absolute error at most half a step, 1/510 (stored units)",
        ),
        Storage::Unorm16 => (
            "unorm16",
            "16-bit unsigned normalized: code = round(value * scale * 65535), ties to even, a sampler reads code / 65535; absolute error at most half a step, 1/131070 (stored units)",
        ),
    };
    let err: serde_json::Map<String, Value> = lut
        .channels
        .iter()
        .zip(&lut.error_estimate)
        .map(|(c, e)| (c.name.clone(), json!(e)))
        .collect();
    let method = crate::table::methods::describe(spec);
    let mut layout = format!(
        "channels interleaved per texel; x (axis 0, u) fastest, then y (axis 1, v, one image row per y){}",
        if dims.len() == 3 { ", then z (axis 2, slice)" } else { "" }
    );
    if dims.len() == 3 {
        layout.push_str(&format!(
            "; image files stack the {} slices vertically: slice z occupies rows [z*{ny}, (z+1)*{ny})",
            dims[2],
            ny = dims[1]
        ));
    }
    let mut quadrature = json!({
        "method": method,
        "tolerance": spec.tolerance,
        "estimated_max_error": err,
        "evaluations": lut.evaluations,
    });
    if let Some(a) = table.accept_error_estimate {
        quadrature["accept_error_estimate"] = json!(a);
        quadrature["accept_error_estimate_meaning"] = json!(
            "the preset accepts per-texel error estimates up to this value, above its tolerance; estimated_max_error is at most this"
        );
    }
    let mut v = json!({
        "schema": SCHEMA,
        "generator": {"name": "brdfbake", "version": VERSION},
        "input_hash": input_hash(table),
        "preset": preset,
        "table": {
            "name": spec.name,
            "kind": spec.kind.name(),
            "description": spec.kind.description(),
            "dimensions": dims.len(),
            "size": dims,
        },
        "model": model_json(spec),
        "axes": axes_json(&lut.axes),
        "channels": channels_json(table, lut),
        "reconstruction": reconstruction(spec),
        "storage": {
            "texel_type": texel_type,
            "rounding": rounding,
            "layout": layout,
            "row_order": "the first row in the file is y = 0 (the first coordinate of axis 1); upload it as the first row in memory, which every graphics API maps to texture coordinate v = 0: no y-flip",
            "sampling": "linear filtering, clamp-to-edge; coordinates per axis as in axes[k].shader_texture_coordinate",
            "scale": table.scale,
            "scale_meaning": "stored texel = value * scale; a shader divides what it samples by scale (1: stored as computed)",
            "ktx2": {
                "channels": "1 -> R, 2 -> RG, 3 -> RGBA with A = 1 (padding), 4 -> RGBA",
                "layout_3d": table.layout_3d,
                "orientation": "KTXorientation rd (1D, 2D and 2D arrays) / rdi (3D textures): the first row is y = 0",
            },
        },
        "quadrature": quadrature,
        "lookup_error": lookup_error(table, lut),
        "files": files.iter().map(|(k, v)| (k.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
    });
    // (only for the normalized-integer storages: float tables keep their sidecars)
    if let Some(step) = spec.storage.quantization_step() {
        let max = spec.storage.unorm_max().unwrap_or(0);
        let measured = crate::encode::unorm::max_rounding_error(lut, spec.storage);
        let st = &mut v["storage"];
        st["quantization_step"] = json!(step);
        st["quantization_step_meaning"] = json!(format!(
            "1/{max}, in stored units (value x scale): the spacing of the values a sampler reads; in the table's values it is quantization_step / scale"
        ));
        st["rounding_error_bound"] = json!(step / 2.0);
        st["rounding_error_bound_meaning"] = json!(
            "quantization_step / 2, in stored units: no stored texel lies farther than this from value x scale (divide by scale for the table's values; lookup_error.texel_error includes it)"
        );
        st["measured_max_rounding_error"] = Value::Object(
            lut.channels
                .iter()
                .zip(&measured)
                .map(|(c, e)| (c.name.clone(), json!(e / table.scale)))
                .collect(),
        );
        st["measured_max_rounding_error_meaning"] = json!(
            "per channel, the largest |code / (2^n - 1) / scale - value| over the texels, in the table's values (value = the baked f32 texel)"
        );
        st["ktx2"]["channels"] = json!(format!(
            "1 -> R, 2 -> RG, 3 -> RGBA with A = 1 (code {max}, padding), 4 -> RGBA"
        ));
        st["png_data"] = json!({
            "channels": "1 -> grey, 2 -> RGB with B = 0 (PNG has no two-channel colour type), 3 -> RGB, 4 -> RGBA",
            "bit_depth": spec.storage.bytes() * 8,
            "layout": "as the EXR and KTX2 rows: the top image row is y = 0; the slices of a 3D table stacked downward; no colour-space chunk (linear data)",
        });
    }
    // the containers' own facts, for the formats written
    let components = crate::encode::texels::components(lut.channels.len());
    // (only when set: tables written as plain ktx2 keep their sidecars)
    if table.formats.contains(&crate::preset::Format::Ktx2Zstd) {
        v["storage"]["ktx2"]["supercompression"] = json!("zstd");
        v["storage"]["ktx2"]["supercompression_meaning"] = json!(
            "supercompressionScheme 2 (Zstandard): the level is one zstd frame; a loader inflates it to the texels before upload (libktx: ktxTexture2_CreateFromMemory; three.js: KTX2Loader; Bevy: the zstd feature)"
        );
    }
    if table.formats.contains(&crate::preset::Format::PngRgbd) {
        v["storage"]["rgbd"] = json!({
            "file": format!("{}.png", spec.name),
            "encoding": "Babylon.js RGBD, 8-bit RGBA PNG: R, G, B = round(255 (v D)^(1/2.2)), A = round(255 D), D = min(floor(max(255/max(R, G, B), 1))/255, 1)",
            "decode": "value = (c/255)^2.2 / (a/255) (Babylon's fromRGBD with its default toLinearSpace = pow 2.2); decoded once to a half-float texture by RGBDTextureTools.ExpandRGBDTexture",
            "max_rounding": crate::encode::rgbd::max_rounding(lut),
            "max_rounding_meaning": "per channel, the most a decoded texel differs from the table's value through the encoding (half a code through the power curve, over D); the table's own values are in its other files",
            "layout": "as png-data: the top image row is y = 0 (load with invertY = false); no colour-space chunk",
        });
    }
    if table.formats.contains(&crate::preset::Format::Dds) {
        let (code, name) = crate::encode::dds::dxgi_format(components, spec.storage);
        let volume = dims.len() == 3 && table.layout_3d == crate::preset::Layout3d::Volume;
        v["storage"]["dds"] = json!({
            "dxgi_format": code,
            "dxgi_format_name": format!("DXGI_FORMAT_{name}"),
            "resource_dimension": if volume { "TEXTURE3D" } else { "TEXTURE2D" },
            "array_size": if dims.len() == 3 && !volume { dims[2] } else { 1 },
            "channels": "as ktx2: 1 -> R, 2 -> RG, 3 -> RGBA with A = 1 (padding), 4 -> RGBA",
            "orientation": "the first row is y = 0, the top row of the DDS image (Direct3D, Vulkan and Metal texture coordinate v = 0): no y-flip; OpenGL loaders that flip DDS images must not flip these",
        });
    }
    // (only when an array format is written: other sidecars stay as they were)
    let notes: Vec<&str> = [
        ("npy", crate::encode::npy::FILE_NOTE),
        ("npz", crate::encode::npz::FILE_NOTE),
        ("bin", crate::encode::bin::FILE_NOTE),
    ]
    .into_iter()
    .filter(|(k, _)| files.iter().any(|(f, _)| f == k))
    .map(|(_, note)| note)
    .collect();
    if !notes.is_empty() {
        let mut array = crate::encode::bin::array_layout(lut, spec.storage);
        array["files"] = json!(notes);
        v["storage"]["array"] = array;
    }
    if spec.kind.is_ltc() {
        v["ltc"] = ltc_section(table, fit);
    }
    // (only when set) the fit `bake` wrote beside the table, as the preset asked for it
    if let Some(f) = &table.fit {
        let mut o = fit_request_json(f);
        o["sidecar"] = json!(format!("{}.fit.json", spec.name));
        v["fit"] = o;
    }
    // (only when set: tables without an engine keep their sidecars)
    if let Some(e) = table.engine {
        v["engine"] = json!({
            "name": e.name(),
            "warnings": crate::engine::warnings(table),
            "guide": "docs/engines.md",
        });
    }
    v
}

/// The `lookup_error` sidecar field: per channel, how far a filtered lookup between texel
/// centres lies from the exact function, with ideal (exact) weights and with the 8-bit
/// weights of hardware filtering. `lut` holds the stored texels (value × scale).
pub fn lookup_error(table: &PresetTable, lut: &Lut) -> Value {
    let spec = &table.spec;
    let hw_axes = table.hardware_filtered_axes();
    let unscale = |v: Vec<f64>| -> Vec<f64> { v.into_iter().map(|x| x / table.scale).collect() };
    let estimate = unscale(lut.interpolation_error_estimate());
    let interpolation = unscale(lut.interpolation_bound());
    let weights = unscale(lut.weight_rounding_bound(hw_axes));
    let relative = match spec.storage {
        Storage::F16 => 2f64.powi(-11),
        // (the baked f32 texel's own rounding; UNORM adds its absolute step below)
        Storage::F32 | Storage::Unorm8 | Storage::Unorm16 => 2f64.powi(-24),
    };
    // UNORM: half a step, in the table's values
    let absolute = spec
        .storage
        .quantization_step()
        .map_or(0.0, |step| step / 2.0 / table.scale);
    let nc = lut.channels.len();
    let max_abs: Vec<f64> = (0..nc)
        .map(|c| {
            lut.data
                .iter()
                .skip(c)
                .step_by(nc.max(1))
                .fold(0.0f64, |m, v| m.max((*v as f64).abs()))
                / table.scale
        })
        .collect();
    let texel: Vec<f64> = (0..nc)
        .map(|c| {
            lut.error_estimate.get(c).copied().unwrap_or(0.0) + relative * max_abs[c] + absolute
        })
        .collect();
    let per_channel = |v: &dyn Fn(usize) -> f64| -> Value {
        Value::Object(
            lut.channels
                .iter()
                .enumerate()
                .map(|(c, ch)| (ch.name.clone(), json!(v(c))))
                .collect(),
        )
    };
    let filtered: Vec<&str> = lut.axes[..hw_axes]
        .iter()
        .map(|a| a.name.as_str())
        .collect();
    json!({
        "meaning": "per channel, the worst-case difference between a linearly filtered lookup inside the hull of the texel centres and the exact function: ideal_filtering with exact weights (CPUs, software rasterizers, brdfbake probe) = interpolation_bound + texel_error, hardware_filtering with weights rounded to multiples of 1/256 (GPUs with 8-bit sub-texel precision, brdfbake probe --filter hardware) = that + weight_rounding_bound; beyond the edge texel centres a lookup returns the edge texels (clamp-to-edge)",
        "ideal_filtering": per_channel(&|c| interpolation[c] + texel[c]),
        "hardware_filtering": per_channel(&|c| interpolation[c] + texel[c] + weights[c]),
        "interpolation_bound": per_channel(&|c| interpolation[c]),
        "interpolation_bound_meaning": "max over cells of (largest - smallest texel at the cell's corners): inside a cell where the function is monotone along each axis (no peak or dip strictly between texel centres) both the function and the interpolant lie within that range (brdfbake verify measures the error at cell middles and says where it is exceeded)",
        "interpolation_estimate": per_channel(&|c| estimate[c]),
        "interpolation_estimate_meaning": "the typical error where the table is smooth at its resolution: max over texels of the sum over axes of |second difference of the texels along the axis| / 8, the linear-interpolation remainder h^2 |f''| / 8 at a cell's middle with h^2 f'' from the texels (exact for data quadratic along each axis)",
        "texel_error": per_channel(&|c| texel[c]),
        "texel_error_meaning": if absolute > 0.0 {
            "quadrature.estimated_max_error plus the f32 rounding of the largest |value| plus the normalized-integer rounding bound (storage.rounding_error_bound / scale)"
        } else {
            "quadrature.estimated_max_error plus the storage rounding of the largest |value|"
        },
        "weight_rounding_bound": per_channel(&|c| weights[c]),
        "weight_rounding_bound_meaning": "sum over the hardware-filtered axes of the largest step between neighbouring texels / 512: the most rounding the weights to 1/256 (by at most 1/512 each) moves a lookup, the interpolant being affine in each weight with a slope of at most the cell's step",
        "hardware_filtered_axes": filtered,
    })
}

/// A few key facts as string pairs for image-file headers.
pub fn header_attributes(preset: &str, table: &PresetTable, lut: &Lut) -> Vec<(String, String)> {
    let spec = &table.spec;
    let mut v = vec![
        ("schema".to_string(), SCHEMA.to_string()),
        ("version".to_string(), VERSION.to_string()),
        ("input_hash".to_string(), input_hash(table)),
        ("preset".to_string(), preset.to_string()),
        ("table".to_string(), spec.name.clone()),
        ("kind".to_string(), spec.kind.name().to_string()),
        ("model".to_string(), model_summary(spec)),
        ("scale".to_string(), format!("{}", table.scale)),
    ];
    // (only for the normalized-integer storages: float tables keep their attributes)
    if spec.storage.is_unorm() {
        v.push(("storage".to_string(), spec.storage.name().to_string()));
    }
    // (only when set)
    if let Some(c) = channels_summary(table) {
        v.push(("channels".to_string(), c));
    }
    for (k, a) in lut.axes.iter().enumerate() {
        let mut text = format!(
            "{} {} {} [{}, {}] {} texels",
            a.name,
            quantity_name(a),
            a.convention.name(),
            a.range[0],
            a.range[1],
            a.size
        );
        // (only when set: linear unclamped axes keep their attribute)
        if a.warp != Warp::Linear {
            text.push_str(&format!(" warp {}", a.warp.name()));
        }
        if let Some([c0, c1]) = a.clamp {
            text.push_str(&format!(" clamp [{c0}, {c1}]"));
        }
        v.push((format!("axis{k}"), text));
    }
    v
}

/// One-line model description, e.g. `ggx / smith-height-correlated / fresnel none`.
pub fn model_summary(spec: &TableSpec) -> String {
    let m = &spec.model;
    if let Some(c) = &m.classic {
        return format!(
            "classic {}",
            serde_json::to_string(c).expect("serializable")
        );
    }
    let mut s = format!(
        "{} / {} / fresnel {}",
        m.ndf.map_or("no specular", |n| n.name()),
        m.masking.name(),
        m.fresnel.name()
    );
    if m.diffuse_weight > 0.0 {
        s.push_str(&format!(
            " + {} {}",
            m.diffuse_model.name(),
            m.diffuse_weight
        ));
    }
    s
}

/// The rows of a per-texel array (axis 1 index, axis 0 fastest within a row) as strings of
/// numbers with 3 significant digits, separated by spaces: the sidecar's fit error (a
/// guide to where the fit is good, compact: 64 strings, not 4096 lines).
pub fn texel_rows(v: &[f32], nx: usize) -> Vec<String> {
    v.chunks(nx.max(1))
        .map(|r| {
            r.iter()
                .map(|x| format!("{:.2e}", *x as f64))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect()
}

/// The inverse of [`texel_rows`]: the values, row after row; `None` if a number is malformed.
pub fn parse_texel_rows(rows: &[Value]) -> Option<Vec<f32>> {
    let mut out = Vec::new();
    for r in rows {
        for t in r.as_str()?.split_whitespace() {
            out.push(t.parse::<f32>().ok()?);
        }
    }
    Some(out)
}

/// The `ltc` sidecar section: the channels and how a shader rebuilds the matrix, the fit's
/// method and settings, and (with `fit`) the per-texel fit error.
fn ltc_section(table: &PresetTable, fit: Option<&Lut>) -> Value {
    let spec = &table.spec;
    if spec.kind == TableKind::LtcSphere {
        return json!({
            "table": "horizon-clipped sphere (Heitz & Hill 2017; Snyder 1996's closed form): value(z, len) = (1/pi) int_cap max(0, w_z) dw / len for the cap of solid-angle radius asin(sqrt(len)) at the angle acos(z) from the normal; max(z, 0) at len = 0",
            "lookup": "uv = ((z - lo_z) / (hi_z - lo_z), (len - lo_len) / (hi_len - lo_len)) remapped per axes[k].shader_texture_coordinate; z is the vector form factor's direction's z, len its length",
        });
    }
    let chans = crate::table::ltc::ltc_channels(spec);
    let index = |c: crate::table::LtcChannel| chans.iter().position(|&x| x == c);
    let mut v = json!({
        "channels": chans.iter().map(|c| c.name()).collect::<Vec<_>>(),
        "normalization": "M^-1 = [[a, 0, b], [0, c, 0], [d, 0, 1]] (rows) divided by its middle entry c: m00 = a/c, m20 = d/c, m02 = b/c, m22 = 1/c (Heitz's ltc_1, three.js' ltc_1, EEVEE's ltc_mat_ggx)",
        "frame": "the normal is +z, the view lies in the xz-plane at positive x: x = normalize(V - N (N.V)), y = cross(N, x)",
        "fit": {
            "method": "deterministic Levenberg-Marquardt on relative residuals of a fixed hemisphere rule's nodes and fixed probe lights, warm-started along the views of each roughness from the largest cos theta_v down (src/kernels/ltc_fit.rs; docs/presets.md, Area-light tables)",
            "rule": crate::table::ltc::fit_options(spec).rule,
            "bounds": "b >= 0 >= d, so that every bilinear lookup between texels is invertible",
        },
    });
    // (only when set, so that GGX tables keep their bytes)
    let opts = crate::table::ltc::fit_options(spec);
    if opts.retro {
        v["fit"]["bounds"] = json!("b <= 0 <= d (the lobe leans toward the view, as sheen scatters back), so that every bilinear lookup between texels is invertible");
    }
    if opts.peak_floor > 0.0 {
        v["fit"]["floor"] = json!(format!(
            "the relative residuals' floor, lit_rms's included: max({:e}, {} * the normalized lobe's peak density) per texel (src/table/ltc.rs, fit_options: an LTC cannot follow this lobe's tails or hole relatively)",
            opts.floor, opts.peak_floor
        ));
    }
    // (with the preset's `channels` the texture's components are those, not ltc.channels:
    // the sidecar's `channels` say what each holds, and no rebuild is spelled out here)
    if table.channels.is_none() && chans.iter().any(|c| c.is_matrix()) {
        let m = [
            crate::table::LtcChannel::M00,
            crate::table::LtcChannel::M20,
            crate::table::LtcChannel::M02,
            crate::table::LtcChannel::M22,
        ]
        .map(index);
        if let [Some(a), Some(b), Some(c), Some(d)] = m {
            let s = |k: usize| ["r", "g", "b", "a"].get(k).copied().unwrap_or("?");
            v["inverse_matrix"] = json!(format!(
                "mat3(vec3(t.{}, 0, t.{}), vec3(0, 1, 0), vec3(t.{}, 0, t.{})) with t the sampled texel (GLSL column-major)",
                s(a), s(b), s(c), s(d)
            ));
        }
    }
    if let Some(f) = fit {
        let nc = f.channels.len().max(1);
        let mut err = serde_json::Map::new();
        for (c, ch) in f.channels.iter().enumerate() {
            let vals: Vec<f32> = f.data.iter().skip(c).step_by(nc).copied().collect();
            let mut sorted: Vec<f64> = vals.iter().map(|&x| x as f64).collect();
            sorted.sort_by(f64::total_cmp);
            let q = |p: f64| {
                sorted
                    .get(((sorted.len() as f64 - 1.0) * p).round() as usize)
                    .copied()
                    .unwrap_or(f64::NAN)
            };
            err.insert(
                ch.name.clone(),
                json!({
                    "meaning": ch.meaning,
                    "median": q(0.5),
                    "p99": q(0.99),
                    "max": q(1.0),
                    "rows": texel_rows(&vals, f.dim(0)),
                }),
            );
        }
        v["fit_error"] = Value::Object(err);
        v["fit_error_layout"] = json!(
            "rows: one string per texture row (axis 1 index), the row's texels along axis 0 separated by spaces, 3 significant digits"
        );
    }
    v
}
