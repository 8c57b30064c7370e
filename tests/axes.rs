//! Axes: warps (`lut::Warp`), clamped axes and the stored axis order (`axis_order`). Every
//! texel holds the function at its warped, clamped coordinate; lookups invert the warp; the
//! sidecar, the EXR header, the shader snippets, `inspect`, `probe` and `verify` all know
//! it; a reordered table is the kind-ordered one transposed.
//!
//! The reference values are closed forms written here (GGX's Smith G1), so a texel placed
//! at the wrong coordinate shows as a wrong value, far above f32 rounding (2^-24 relative).

#[path = "common/cli.rs"]
mod cli;

use brdfbake::lut::{Axis, Convention, Quantity, Warp};
use brdfbake::model::{Fresnel, Masking, NdfKind, RoughnessQuantity};
use brdfbake::table::{bake, ModelSpec, Storage, TableKind, TableSpec};
use cli::run;
use std::f64::consts::FRAC_PI_2;

/// GGX Smith G1 (Heitz 2014, eq. 72): 2/(1 + √(1 + α² tan²θ)).
fn g1_ggx(mu: f64, alpha: f64) -> f64 {
    if mu <= 0.0 {
        return 0.0;
    }
    let t2 = (1.0 - mu * mu) / (mu * mu);
    2.0 / (1.0 + (1.0 + alpha * alpha * t2).sqrt())
}

fn g1_spec(cos: Axis) -> TableSpec {
    TableSpec {
        name: "g1".into(),
        kind: TableKind::G1,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking: Masking::SmithSeparable,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes: vec![
            cos,
            Axis::new(
                "roughness",
                Quantity::Roughness(RoughnessQuantity::Alpha),
                3,
                [0.2, 0.8],
                Convention::Endpoints,
            ),
        ],
        dfg_layout: None,
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-9,
    }
}

fn warped(warp: Warp, size: usize, range: [f64; 2], convention: Convention) -> Axis {
    Axis {
        warp,
        ..Axis::new("cos_theta", Quantity::Cosine, size, range, convention)
    }
}

/// The coordinate of texel i as each engine writes it.
fn expected_coordinate(warp: Warp, p: f64) -> f64 {
    match warp {
        Warp::Linear => p,
        Warp::SqrtOneMinus => 1.0 - p * p,
        Warp::Sqrt => p * p,
        Warp::Acos => p.cos(),
        Warp::Square => p.sqrt(),
        Warp::OneMinus => 1.0 - p,
        Warp::CriticalAngle => unreachable!("not on a g1 table"),
    }
}

#[test]
fn texels_sit_at_the_warped_coordinates() {
    for (warp, range) in [
        (Warp::Linear, [0.0, 1.0]),
        (Warp::SqrtOneMinus, [0.0, 1.0]),
        (Warp::Sqrt, [0.0, 1.0]),
        (Warp::Acos, [0.0, FRAC_PI_2]),
        (Warp::Square, [0.0, 1.0]),
        (Warp::OneMinus, [0.0, 1.0]),
    ] {
        for conv in [Convention::Centers, Convention::Endpoints] {
            let n = 9;
            let ax = warped(warp, n, range, conv);
            let lut = bake(&g1_spec(ax.clone())).unwrap();
            for j in 0..3 {
                let alpha = 0.2 + 0.3 * j as f64;
                for i in 0..n {
                    let t = match conv {
                        Convention::Centers => (i as f64 + 0.5) / n as f64,
                        Convention::Endpoints => i as f64 / (n - 1) as f64,
                    };
                    let p = range[0] + (range[1] - range[0]) * t;
                    let x = expected_coordinate(warp, p);
                    assert!(
                        (ax.coord(i) - x).abs() <= 1e-15,
                        "{warp:?} {conv:?} texel {i}: coordinate {} against {x}",
                        ax.coord(i)
                    );
                    let want = g1_ggx(x, alpha);
                    let got = lut.texel([i, j, 0], 0) as f64;
                    assert!(
                        (got - want).abs() <= 1e-7,
                        "{warp:?} {conv:?} texel [{i}, {j}]: {got} against G1({x}, {alpha}) = {want}"
                    );
                    // a lookup at the texel's coordinate returns the texel
                    let back = lut.lookup(&[x, alpha])[0];
                    assert!(
                        (back - got).abs() <= 1e-6 * got.abs().max(1e-3),
                        "{warp:?} {conv:?}: lookup at texel {i}'s coordinate gave {back}, the texel holds {got}"
                    );
                }
                // halfway between two texels in p, the lookup is their mean
                let (pa, pb) = (
                    brdfbake::lut::Axis::parameter(&ax, 3),
                    brdfbake::lut::Axis::parameter(&ax, 4),
                );
                let mid = expected_coordinate(warp, 0.5 * (pa + pb));
                let want = 0.5 * (lut.texel([3, j, 0], 0) as f64 + lut.texel([4, j, 0], 0) as f64);
                let got = lut.lookup(&[mid, alpha])[0];
                assert!(
                    (got - want).abs() <= 1e-6,
                    "{warp:?} {conv:?}: lookup between texels 3 and 4 gave {got}, want {want}"
                );
            }
        }
    }
}

/// A roughness axis takes the reversal `one-minus` (Godot's DFG rows run from roughness 1
/// down) and no other warp: its texels hold G1 at α = (1 − p)² and lookups find them.
#[test]
fn a_roughness_axis_runs_backwards_with_one_minus() {
    let mut spec = g1_spec(warped(Warp::Linear, 5, [0.0, 1.0], Convention::Centers));
    spec.axes[1] = Axis {
        warp: Warp::OneMinus,
        ..Axis::new(
            "roughness",
            Quantity::Roughness(RoughnessQuantity::Perceptual),
            4,
            [0.0, 1.0],
            Convention::Centers,
        )
    };
    let lut = bake(&spec).unwrap();
    for j in 0..4 {
        let r = 1.0 - (j as f64 + 0.5) / 4.0;
        assert!((spec.axes[1].alpha(j).unwrap() - r * r).abs() < 1e-15);
        for i in 0..5 {
            let mu = spec.axes[0].coord(i);
            let got = lut.texel([i, j, 0], 0) as f64;
            assert!(
                (got - g1_ggx(mu, r * r)).abs() <= 1e-7,
                "texel [{i}, {j}]: {got}"
            );
            assert!((lut.lookup(&[mu, r])[0] - got).abs() <= 1e-6);
        }
    }
    spec.axes[1].warp = Warp::Sqrt;
    let e = spec.validate().unwrap_err();
    assert!(e.contains("one-minus"), "{e}");
}

#[test]
fn a_clamped_axis_evaluates_inside_the_clamp() {
    let ax = Axis {
        clamp: Some([1e-2, 0.99]),
        ..Axis::new(
            "cos_theta",
            Quantity::Cosine,
            5,
            [0.0, 1.0],
            Convention::Endpoints,
        )
    };
    let lut = bake(&g1_spec(ax.clone())).unwrap();
    let alpha = 0.2;
    let at = |i: usize| lut.texel([i, 0, 0], 0) as f64;
    assert!(
        (at(0) - g1_ggx(1e-2, alpha)).abs() <= 1e-7,
        "texel 0 at 1e-2"
    );
    assert!(
        (at(4) - g1_ggx(0.99, alpha)).abs() <= 1e-7,
        "texel 4 at 0.99"
    );
    assert!(
        (at(2) - g1_ggx(0.5, alpha)).abs() <= 1e-7,
        "texel 2 unclamped"
    );
    // the exact value the table stands for at x = 0 is the clamped one
    let (v, _) = brdfbake::readback::exact_at(&g1_spec(ax), &[0.0, alpha], 1e-9).unwrap();
    assert!((v[0] - g1_ggx(1e-2, alpha)).abs() <= 1e-12);
}

#[test]
fn bad_warps_and_clamps_are_named() {
    let cases: &[(&str, &[&str])] = &[
        (
            r#""cos_theta": {"size": 4, "warp": "sqrt-one-minus", "range": [0, 2]}"#,
            &["axes.cos_theta.range", "[0, 1]", "sqrt(1 - x)"],
        ),
        (
            r#""cos_theta": {"size": 4, "warp": "acos", "range": [0, 2]}"#,
            &["axes.cos_theta.range", "acos"],
        ),
        (
            r#""cos_theta": {"size": 4, "warp": "log"}"#,
            &["axes.cos_theta.warp", "sqrt-one-minus"],
        ),
        (
            r#""cos_theta": {"size": 4, "clamp": [0.5]}"#,
            &["axes.cos_theta.clamp", "two numbers"],
        ),
        (
            r#""cos_theta": {"size": 4, "clamp": [0.5, 0.1]}"#,
            &["axes.cos_theta.clamp", "lo <= hi"],
        ),
        (
            r#""cos_theta": {"size": 4, "clamp": [-1, 1]}"#,
            &["axes.cos_theta.clamp", "within [0, 1]"],
        ),
    ];
    for (axis, want) in cases {
        let text = format!(
            r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "g", "kind": "g1",
                "model": {{"ndf": "ggx"}},
                "axes": {{{axis}, "roughness": {{"size": 4, "quantity": "alpha", "warp": "sqrt"}}}}}}]}}"#
        );
        // (the roughness axis' warp is wrong too, but the cosine axis comes first)
        let e = match brdfbake::preset::parse(&text, "p.json", "p") {
            Err(e) => e.to_string(),
            Ok(_) => panic!("{axis}: accepted"),
        };
        for w in *want {
            assert!(e.contains(w), "{axis}: {e:?} lacks {w:?}");
        }
    }
    let text = r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "g", "kind": "g1",
        "model": {"ndf": "ggx"},
        "axes": {"cos_theta": {"size": 4}, "roughness": {"size": 4, "quantity": "alpha", "warp": "sqrt"}}}]}"#;
    let e = brdfbake::preset::parse(text, "p.json", "p")
        .expect_err("a warped roughness axis")
        .to_string();
    assert!(
        e.contains("axes.roughness.warp") && e.contains("cosine and fresnel axes only"),
        "{e}"
    );
}

/// The CLI end to end: a warped, clamped albedo table bakes, its sidecar and EXR header
/// say so, `inspect` shows it, `probe` samples through the warp, `verify --all` passes, and
/// the GLSL snippet computes the warp.
#[test]
fn warped_tables_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let w = dir.path();
    std::fs::write(
        w.join("eevee-like.json"),
        r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "e", "kind": "albedo",
            "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
            "axes": {"cos_theta_v": {"size": 16, "convention": "endpoints", "warp": "sqrt-one-minus", "clamp": [1e-4, 0.9999]},
                     "roughness": {"size": 8, "quantity": "perceptual", "convention": "endpoints", "range": [0, 1]}},
            "formats": ["exr", "ktx2", "glsl", "wgsl"]}]}"#,
    )
    .unwrap();
    let o = run(w, &["bake", "eevee-like.json", "--out", "out"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let sidecar: serde_json::Value =
        serde_json::from_slice(&std::fs::read(w.join("out/eevee-like/e.json")).unwrap()).unwrap();
    let ax = &sidecar["axes"][0];
    assert_eq!(ax["warp"]["name"], "sqrt-one-minus", "{ax}");
    assert_eq!(ax["clamp"], serde_json::json!([1e-4, 0.9999]), "{ax}");
    // texel 0 sits at p = 0 (normal incidence), evaluated at 0.9999; the last at grazing, 1e-4
    assert_eq!(ax["coordinates"][0], 0.9999);
    assert_eq!(ax["coordinates"][15], 1e-4);
    assert_eq!(ax["nominal_coordinates"][0], 1.0);
    let glsl = std::fs::read_to_string(w.join("out/eevee-like/e.glsl")).unwrap();
    assert!(glsl.contains("sqrt(1.0 - clamp("), "{glsl}");

    let o = run(w, &["inspect", "out/eevee-like/e.exr"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && out.contains("sqrt-one-minus"),
        "{out}"
    );

    for file in ["out/eevee-like/e.exr", "out/eevee-like/e.ktx2"] {
        let o = run(
            w,
            &[
                "probe",
                file,
                "--at",
                "cos_theta_v=0.75,roughness=0.5",
                "--json",
            ],
        );
        assert!(o.status.success(), "{}", cli::stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let diff = v["channels"][0]["difference"].as_f64().unwrap();
        // interpolation error of a 16 × 8 table of E: well under 1e-2
        assert!(diff.abs() < 1e-2, "{v}");
    }
    let o = run(w, &["verify", "out/eevee-like/e.json", "--all"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
}

/// `axis_order` stores the axes in an engine's order (Cycles and three.js put roughness
/// along u): the stored texels are the kind-ordered table transposed, the sidecar lists the
/// axes in stored order, and `verify`, `probe` and `bake --check` follow it.
#[test]
fn axis_order_transposes_the_stored_table() {
    let dir = tempfile::tempdir().unwrap();
    let w = dir.path();
    let table = |order: &str| {
        format!(
            r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "dfg", "kind": "dfg", "layout": "karis",
            "model": {{"ndf": "ggx", "masking": "smith-height-correlated"}},
            "axes": {{"cos_theta_v": {{"size": 6}}, "roughness": {{"size": 4, "quantity": "perceptual"}}}}{order},
            "formats": ["exr", "ktx2", "glsl"]}}]}}"#
        )
    };
    std::fs::write(w.join("kind.json"), table("")).unwrap();
    std::fs::write(
        w.join("swapped.json"),
        table(r#", "axis_order": ["roughness", "cos_theta_v"]"#),
    )
    .unwrap();
    std::fs::write(
        w.join("same.json"),
        table(r#", "axis_order": ["cos_theta_v", "roughness"]"#),
    )
    .unwrap();
    for p in ["kind.json", "swapped.json", "same.json"] {
        let o = run(w, &["bake", p, "--out", "out"]);
        assert!(o.status.success(), "{p}: {}", cli::stderr(&o));
    }
    let read = |p: &str| brdfbake::readback::read(&w.join(format!("out/{p}/dfg.exr"))).unwrap();
    let (a, b, same) = (read("kind"), read("swapped"), read("same"));
    let (la, lb) = (a.lut.unwrap(), b.lut.unwrap());
    assert_eq!(lb.axes[0].name, "roughness");
    assert_eq!(lb.axes[1].name, "cos_theta_v");
    assert_eq!((lb.dim(0), lb.dim(1)), (4, 6));
    for i in 0..6 {
        for j in 0..4 {
            for c in 0..2 {
                assert_eq!(
                    la.texel([i, j, 0], c),
                    lb.texel([j, i, 0], c),
                    "texel [{i}, {j}] channel {c}"
                );
            }
        }
    }
    // the kind's own order is no reordering: the same texels and input hash as the preset
    // without the field
    assert_eq!(la.data, same.lut.unwrap().data);
    let hash = |p: &str| -> serde_json::Value {
        serde_json::from_slice::<serde_json::Value>(
            &std::fs::read(w.join(format!("out/{p}/dfg.json"))).unwrap(),
        )
        .unwrap()["input_hash"]
            .clone()
    };
    assert_eq!(hash("kind"), hash("same"));
    assert_ne!(hash("kind"), hash("swapped"));
    let sidecar: serde_json::Value =
        serde_json::from_slice(&std::fs::read(w.join("out/swapped/dfg.json")).unwrap()).unwrap();
    assert_eq!(sidecar["axes"][0]["name"], "roughness", "{sidecar}");
    let glsl = std::fs::read_to_string(w.join("out/swapped/dfg.glsl")).unwrap();
    assert!(
        glsl.contains(
            "dfg_lookup(highp sampler2D lut, highp float roughness, highp float cos_theta_v)"
        ),
        "{glsl}"
    );
    for f in ["out/swapped/dfg.json", "out/swapped/dfg.ktx2"] {
        let o = run(w, &["verify", f, "--all"]);
        assert!(o.status.success(), "{f}: {}", cli::stderr(&o));
    }
    let o = run(
        w,
        &[
            "probe",
            "out/swapped/dfg.exr",
            "--at",
            "cos_theta_v=0.5,roughness=0.375",
            "--json",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // the interpolation error of a 6 × 4 split sum, well under 0.05
    assert!(
        v["channels"][0]["difference"].as_f64().unwrap().abs() < 0.05,
        "{v}"
    );
    let o = run(w, &["bake", "swapped.json", "--out", "out", "--check"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));

    // bad orders are named
    for (order, want) in [
        (r#"["roughness"]"#, "every axis"),
        (r#"["roughness", "roughness"]"#, "listed twice"),
        (r#"["roughness", "cos_theta"]"#, "not an axis"),
    ] {
        let text = table(&format!(r#", "axis_order": {order}"#));
        let e = brdfbake::preset::parse(&text, "p.json", "p")
            .expect_err(order)
            .to_string();
        assert!(e.contains("axis_order") && e.contains(want), "{order}: {e}");
    }
}

/// A clamped roughness axis repeats its end value in every row beyond the clamp: tables baked
/// by lines (a GGX split sum, a Charlie sheen albedo with Conty–Kulla's Λ, 128 × 64 with
/// α = r² clamped to [0.07, 1]) compute those rows once and hold the same bits in each, and
/// each such texel agrees with the texel-by-texel value at the clamped α within the two
/// estimates (the table's largest and the adaptive integrator's) plus f32 rounding.
#[test]
fn clamped_rows_are_computed_once_and_hold_the_clamped_value() {
    let clamp = 0.07f64.sqrt();
    for (kind, ndf, masking) in [
        (TableKind::Dfg, NdfKind::Ggx, Masking::SmithHeightCorrelated),
        (TableKind::Albedo, NdfKind::Charlie, Masking::ContyKulla),
    ] {
        let mut rough = Axis::new(
            "roughness",
            Quantity::Roughness(RoughnessQuantity::Perceptual),
            64,
            [0.0, 1.0],
            Convention::Centers,
        );
        rough.clamp = Some([clamp, 1.0]);
        let spec = TableSpec {
            name: "t".into(),
            kind,
            model: ModelSpec {
                ndf: Some(ndf),
                masking,
                fresnel: Fresnel::None,
                diffuse_weight: 0.0,
                diffuse_model: brdfbake::model::DiffuseModel::Lambert,
                classic: None,
            },
            axes: vec![
                Axis::new(
                    "cos_theta_v",
                    Quantity::Cosine,
                    128,
                    [0.0, 1.0],
                    Convention::Centers,
                ),
                rough,
            ],
            dfg_layout: (kind == TableKind::Dfg).then_some(brdfbake::table::DfgLayout::Karis),
            cloth: false,
            cloth_alpha_min: None,
            storage: Storage::F32,
            tolerance: 1e-7,
            ..g1_spec(Axis::new(
                "cos_theta",
                Quantity::Cosine,
                2,
                [0.0, 1.0],
                Convention::Centers,
            ))
        };
        let lut = bake(&spec).unwrap();
        let clamped: Vec<usize> = (0..64)
            .filter(|&j| (j as f64 + 0.5) / 64.0 <= clamp)
            .collect();
        assert!(
            clamped.len() > 10,
            "{kind:?}: {} clamped rows",
            clamped.len()
        );
        let nch = lut.channels.len();
        let row = |j: usize| &lut.data[j * 128 * nch..(j + 1) * 128 * nch];
        for &j in &clamped {
            assert_eq!(row(j), row(clamped[0]), "{kind:?}: row {j}");
        }
        let alpha = 0.07;
        for i in [0, 5, 40, 127] {
            let mu = (i as f64 + 0.5) / 128.0;
            let s = brdfbake::model::Specular {
                ndf: brdfbake::model::Ndf::new(ndf, alpha).unwrap(),
                masking,
                fresnel: Fresnel::None,
            };
            let (want, want_err): (Vec<f64>, f64) = if kind == TableKind::Dfg {
                let (v, e, _) = brdfbake::table::dfg::split_sum_adaptive(&s, mu, 1e-10);
                (v.to_vec(), e[0].max(e[1]))
            } else {
                let b = brdfbake::model::Brdf {
                    specular: Some(s),
                    diffuse_weight: 0.0,
                    diffuse: brdfbake::model::DiffuseLobe::Lambert,
                };
                let (v, e, _) = brdfbake::table::albedo::directional_albedo_adaptive(&b, mu, 1e-10);
                (v.to_vec(), e[0])
            };
            for (c, w) in want.iter().enumerate() {
                let got = lut.texel([i, clamped[3], 0], c) as f64;
                let bound = lut.error_estimate[c] + want_err + w.abs() * 2f64.powi(-24);
                assert!(
                    (got - w).abs() <= bound,
                    "{kind:?} texel {i} channel {c}: {got} vs {w} (bound {bound})"
                );
            }
        }
    }
}

/// The critical-angle warp (EEVEE's `btdf_split_sum_ggx` view axis), whose parameter
/// depends on the relative index η of the texel's fresnel coordinate through the critical
/// cosine c = √(1 − η²): texel p sits at t = 2p − 1, x = c + t·c (t ≤ 0) or c + t·(1 − c)
/// (t > 0), and the inverse p = x/(2c) (x ≤ c) or 1/2 + (x − c)/(2(1 − c)). The inverse
/// undoes the texel formula (both in f64: within 1e-15 for c away from 0 and 1), x = c sits
/// at p = 1/2 for every c, and η ≥ 1 has no critical angle (c = 0). Negative control: the
/// inverse at the wrong slice's c does not give back p.
#[test]
fn critical_angle_warp_inverts_at_every_critical_cosine() {
    use brdfbake::lut::critical_cosine;
    assert_eq!(critical_cosine(1.0), 0.0);
    assert_eq!(critical_cosine(1.5), 0.0);
    assert!((critical_cosine(0.6) - 0.8).abs() <= 1e-15);
    let w = Warp::CriticalAngle;
    for c in [0.05, 0.3, 0.5, 0.8, 0.99] {
        assert!((w.coordinate_at(0.5, c) - c).abs() <= 1e-15);
        assert!((w.parameter_at(c, c) - 0.5).abs() <= 1e-15);
        assert_eq!(w.coordinate_at(0.0, c), 0.0);
        assert!((w.coordinate_at(1.0, c) - 1.0).abs() <= 1e-15);
        for i in 0..=20 {
            let p = i as f64 / 20.0;
            let x = w.coordinate_at(p, c);
            let t = 2.0 * p - 1.0;
            let want = c + t * if t > 0.0 { 1.0 - c } else { c };
            assert!((x - want).abs() <= 1e-15, "c {c} p {p}: {x} vs {want}");
            assert!(
                (w.parameter_at(x, c) - p).abs() <= 1e-14,
                "c {c} p {p}: inverse {}",
                w.parameter_at(x, c)
            );
        }
        let wrong = w.parameter_at(w.coordinate_at(0.25, c), 1.0 - c);
        if (c - 0.5).abs() > 0.1 {
            assert!((wrong - 0.25).abs() > 0.01, "c {c}: {wrong}");
        }
    }
}

/// A critical-angle axis is accepted only on a dielectric table's view axis (it needs the
/// fresnel axis' η), and a slice whose texels reach cos θ = 0 unclamped is named with its
/// index and η; the square warp applies to cosine and fresnel axes.
#[test]
fn critical_angle_warp_is_refused_where_it_has_no_meaning() {
    let g1 = r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "g", "kind": "g1",
        "model": {"ndf": "ggx"},
        "axes": {"cos_theta": {"size": 4, "warp": "critical-angle"}, "roughness": {"size": 4, "quantity": "alpha"}}}]}"#;
    let e = brdfbake::preset::parse(g1, "p.json", "p")
        .expect_err("critical-angle on a g1 table")
        .to_string();
    assert!(
        e.contains("axes.cos_theta.warp") && e.contains("dielectric-btdf"),
        "{e}"
    );
    let btdf = |cos: &str| {
        format!(
            r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "t", "kind": "dielectric-btdf",
            "model": {{"ndf": "ggx", "masking": "smith-separable"}},
            "axes": {{"cos_theta_v": {cos}, "roughness": {{"size": 3, "quantity": "perceptual", "range": [0.2, 0.8], "convention": "endpoints"}},
                     "fresnel": {{"size": 3, "quantity": "eta", "warp": "square", "range": [0.25, 1], "convention": "endpoints"}}}}}}]}}"#
        )
    };
    let e = brdfbake::preset::parse(
        &btdf(r#"{"size": 5, "warp": "critical-angle", "convention": "endpoints"}"#),
        "p.json",
        "p",
    )
    .expect_err("a texel at cos 0")
    .to_string();
    assert!(
        e.contains("axes.cos_theta_v") && e.contains("cosine 0"),
        "{e}"
    );
    let ok = brdfbake::preset::parse(
        &btdf(r#"{"size": 5, "warp": "critical-angle", "convention": "endpoints", "clamp": [1e-3, 1]}"#),
        "p.json",
        "p",
    )
    .expect("clamped: accepted");
    // slice 0: eta = sqrt(0.25) = 0.5, c = sqrt(0.75); texel 2 sits at c
    let t = &ok.tables[0];
    let mu = brdfbake::table::dielectric::view_cosine(&t.spec, 2, 0);
    assert!((mu - 0.75f64.sqrt()).abs() <= 1e-15, "{mu}");
    let last = brdfbake::table::dielectric::view_cosine(&t.spec, 2, 2);
    assert!((last - 1e-3).abs() <= 1e-15, "eta = 1: c = 0, {last}");
}

/// The CLI end to end on a small table with EEVEE's btdf axes (η² along u, the
/// critical-angle view axis along v, roughness layers): the sidecar lists the view axis'
/// coordinates per fresnel texel, the GLSL snippet computes the critical cosine and the
/// remap, `inspect` names the warps, `probe` samples through them (interpolation error of a
/// 6 × 9 × 3 table of R, T: under 0.1), and `verify --all` recomputes every texel at its own
/// coordinates.
#[test]
fn critical_angle_tables_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let w = dir.path();
    std::fs::write(
        w.join("btdf.json"),
        r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "t", "kind": "dielectric-btdf",
            "model": {"ndf": "ggx", "masking": "smith-separable"},
            "axes": {"cos_theta_v": {"size": 9, "convention": "endpoints", "warp": "critical-angle", "clamp": [1e-4, 0.9999]},
                     "roughness": {"size": 3, "quantity": "perceptual", "convention": "endpoints", "range": [0.3, 0.9]},
                     "fresnel": {"size": 6, "quantity": "eta", "warp": "square", "range": [0.2, 1], "convention": "endpoints"}},
            "axis_order": ["fresnel", "cos_theta_v", "roughness"],
            "formats": ["exr", "glsl"]}]}"#,
    )
    .unwrap();
    let o = run(w, &["bake", "btdf.json", "--out", "out"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let sidecar: serde_json::Value =
        serde_json::from_slice(&std::fs::read(w.join("out/btdf/t.json")).unwrap()).unwrap();
    let ax = &sidecar["axes"][1];
    assert_eq!(ax["warp"]["name"], "critical-angle", "{ax}");
    // fresnel texel 0: eta^2 = 0.2, c = sqrt(0.8); view texel 4 (p = 1/2) sits at c
    let c0 = 0.8f64.sqrt();
    let at = ax["coordinates"][0][4].as_f64().unwrap();
    assert!((at - c0).abs() <= 1e-15, "{ax}");
    // fresnel texel 5: eta = 1, c = 0: the lower half at 0, clamped to 1e-4
    assert_eq!(ax["coordinates"][5][0], 1e-4, "{ax}");
    let glsl = std::fs::read_to_string(w.join("out/btdf/t.glsl")).unwrap();
    assert!(
        glsl.contains("sqrt(max((1.0 - eta") && glsl.contains(" * clamp("),
        "{glsl}"
    );
    let o = run(w, &["inspect", "out/btdf/t.exr"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && out.contains("critical-angle") && out.contains("square"),
        "{out}"
    );
    let o = run(
        w,
        &[
            "probe",
            "out/btdf/t.exr",
            "--at",
            "fresnel=0.7,cos_theta_v=0.6,roughness=0.5",
            "--json",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    for c in 0..2 {
        let diff = v["channels"][c]["difference"].as_f64().unwrap();
        assert!(diff.abs() < 0.1, "{v}");
    }
    let o = run(w, &["verify", "out/btdf/t.json", "--all"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
}
