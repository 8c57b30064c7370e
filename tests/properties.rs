//! Property tests (proptest) of the preset parser and of the model's parameters:
//!
//! - the parser never panics, on arbitrary text and on JSON built from the preset's own
//!   vocabulary (which reaches far deeper into validation than random bytes);
//! - a valid preset round-trips: what the parser returns is what the JSON said, and the
//!   sidecar written for it rebuilds a table with the same input hash;
//! - for every accepted α (the documented [MIN_ALPHA, MAX_ALPHA], narrowed per NDF) and every
//!   direction: D ≥ 0 and finite, G1 and G2 in [0, 1].
//!
//! - any single changed byte of a sealed sidecar or of a file it lists is found by its digest.
//!
//! Case counts are kept small so the file runs in seconds (CI); failures print the
//! minimized input.

use brdfbake::meta;
use brdfbake::model::ndf::{MAX_ALPHA, MIN_ALPHA};
use brdfbake::model::{Masking, Ndf, NdfKind};
use brdfbake::preset;
use brdfbake::readback::table_from_sidecar;
use proptest::prelude::*;
use serde_json::{json, Map, Value};

/// Keys and string values a preset uses: random JSON over them gets past the syntax and
/// shape checks into field validation.
const WORDS: &[&str] = &[
    "schema",
    "brdfbake.preset/1",
    "tables",
    "name",
    "kind",
    "model",
    "axes",
    "size",
    "range",
    "quantity",
    "convention",
    "ndf",
    "masking",
    "fresnel",
    "type",
    "eta",
    "f0",
    "diffuse",
    "tolerance",
    "storage",
    "formats",
    "scale",
    "layout",
    "cloth",
    "description",
    "cos_theta",
    "cos_theta_v",
    "cos_theta_l",
    "cos_theta_h",
    "n_dot_l",
    "n_dot_h",
    "n_dot_v",
    "roughness",
    "g1",
    "g2",
    "ndf",
    "dfg",
    "albedo",
    "albedo-avg",
    "vgroove",
    "ggx",
    "beckmann",
    "gaussian",
    "blinn-phong",
    "charlie",
    "alpha",
    "perceptual",
    "cook-torrance-m",
    "blinn-phong-exponent",
    "smith-separable",
    "smith-height-correlated",
    "ashikhmin",
    "v-groove",
    "schlick",
    "dielectric",
    "f16",
    "f32",
    "exr",
    "ktx2",
    "png",
    "h",
    "rs",
    "glsl",
    "hlsl",
    "wgsl",
    "centers",
    "endpoints",
    "filament",
    "karis",
    "array",
    "",
];

fn word() -> impl Strategy<Value = String> {
    prop::sample::select(WORDS).prop_map(String::from)
}

/// Numbers a hostile preset would use: 0, negatives, huge, tiny, fractions, typical sizes.
fn number() -> impl Strategy<Value = Value> {
    prop_oneof![
        (0i64..20).prop_map(|n| json!(n)),
        any::<i64>().prop_map(|n| json!(n)),
        any::<u64>().prop_map(|n| json!(n)),
        prop::sample::select(vec![
            0.0, -0.0, -1.0, 1e-300, 1e-12, 1e-9, 0.5, 1.0, 1.5, 100.0, 200.0, 4096.0, 1e30, 1e300,
            -1e300
        ])
        .prop_map(|x| json!(x)),
        (-2.0f64..2.0).prop_map(|x| json!(x)),
    ]
}

fn json_value() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        number(),
        word().prop_map(Value::String),
    ];
    leaf.prop_recursive(5, 64, 6, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..4).prop_map(Value::Array),
            prop::collection::vec((word(), inner), 0..6)
                .prop_map(|kv| Value::Object(kv.into_iter().collect::<Map<_, _>>())),
        ]
    })
}

/// A preset-shaped document: the schema and a `tables` array of random objects.
fn preset_like() -> impl Strategy<Value = Value> {
    prop::collection::vec(json_value(), 0..3)
        .prop_map(|tables| json!({"schema": "brdfbake.preset/1", "tables": tables}))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Arbitrary text: an error or a preset, never a panic.
    #[test]
    fn parser_never_panics_on_text(text in ".{0,300}") {
        let _ = preset::parse(&text, "p.json", "p");
    }

    /// Random JSON over the preset vocabulary, at the top level and inside `tables`: an
    /// error or a preset whose tables all hash (metadata can be written), never a panic.
    #[test]
    fn parser_never_panics_on_preset_like_json(v in prop_oneof![json_value(), preset_like()]) {
        let text = serde_json::to_string(&v).unwrap();
        if let Ok(p) = preset::parse(&text, "p.json", "p") {
            for t in &p.tables {
                prop_assert!(t.spec.validate().is_ok());
                let _ = meta::input_hash(t);
            }
        }
    }
}

/// A valid one-table preset of a closed-form kind (fast to bake) with random sizes, ranges
/// and roughness parametrization; returns (JSON, kind, sizes, ranges).
#[allow(clippy::type_complexity)]
fn valid_preset() -> impl Strategy<Value = (Value, String, Vec<usize>, Vec<[f64; 2]>)> {
    let kind = prop::sample::select(vec!["ndf", "g1", "g2"]);
    let ndf = prop::sample::select(vec!["ggx", "beckmann"]);
    let quantity = prop::sample::select(vec!["alpha", "perceptual"]);
    (
        kind,
        ndf,
        quantity,
        prop::collection::vec(1usize..9, 3),
        prop::collection::vec((0.01f64..0.5, 0.5f64..1.0), 3),
        prop::sample::select(vec!["f32", "f16"]),
    )
        .prop_map(|(kind, ndf, q, sizes, ranges, storage)| {
            let cos_names: &[&str] = match kind {
                "ndf" => &["cos_theta_h"],
                "g1" => &["cos_theta"],
                _ => &["cos_theta_v", "cos_theta_l"],
            };
            let mut axes = Map::new();
            let mut all_sizes = Vec::new();
            let mut all_ranges = Vec::new();
            for (i, name) in cos_names.iter().enumerate() {
                let r = [ranges[i].0, ranges[i].1];
                axes.insert(name.to_string(), json!({"size": sizes[i], "range": r}));
                all_sizes.push(sizes[i]);
                all_ranges.push(r);
            }
            let r = [ranges[2].0, ranges[2].1];
            axes.insert(
                "roughness".into(),
                json!({"size": sizes[2], "range": r, "quantity": q}),
            );
            all_sizes.push(sizes[2]);
            all_ranges.push(r);
            let mut model = json!({"ndf": ndf});
            if kind == "g2" {
                model["masking"] = json!("smith-height-correlated");
            }
            // D reaches 1/(π α²) ≫ the f16 maximum at small α: NDF tables are stored f32
            let storage = if kind == "ndf" { "f32" } else { storage };
            let doc = json!({
                "schema": "brdfbake.preset/1",
                "tables": [{"name": "t", "kind": kind, "storage": storage, "model": model, "axes": axes}]
            });
            (doc, kind.to_string(), all_sizes, all_ranges)
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// A valid preset parses to what it says, and its sidecar rebuilds the same table.
    #[test]
    fn valid_presets_round_trip((doc, kind, sizes, ranges) in valid_preset()) {
        let text = serde_json::to_string_pretty(&doc).unwrap();
        let p = preset::parse(&text, "p.json", "p").map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert_eq!(p.tables.len(), 1);
        let t = &p.tables[0];
        prop_assert_eq!(t.spec.kind.name(), kind.as_str());
        let got: Vec<usize> = t.spec.axes.iter().map(|a| a.size).collect();
        prop_assert_eq!(got, sizes);
        let got: Vec<[f64; 2]> = t.spec.axes.iter().map(|a| a.range).collect();
        prop_assert_eq!(got, ranges);
        // bake (closed-form kinds, ≤ 512 texels) and rebuild the table from its sidecar
        let lut = brdfbake::bake(&t.spec).map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert!(lut.data.iter().all(|v| v.is_finite()));
        let sidecar = meta::metadata("p", t, &lut, &[]);
        let back = table_from_sidecar(&sidecar).map_err(TestCaseError::fail)?;
        prop_assert_eq!(meta::input_hash(&back), meta::input_hash(t));
        // and the JSON text of the sidecar parses back to the same document
        let again: Value = serde_json::from_str(&serde_json::to_string(&sidecar).unwrap()).unwrap();
        prop_assert_eq!(again, sidecar);
    }
}

/// α log-uniform over the documented accepted range [MIN_ALPHA, MAX_ALPHA].
fn alpha() -> impl Strategy<Value = f64> {
    (MIN_ALPHA.ln()..=MAX_ALPHA.ln()).prop_map(|l| l.exp().clamp(MIN_ALPHA, MAX_ALPHA))
}

/// The upper α limit an NDF documents for itself (Blinn-Phong: s = 2/α² − 2 ≥ 0 needs
/// α ≤ 1; the Gaussian's m ≤ 10 radians), else MAX_ALPHA.
fn own_limit(kind: NdfKind) -> f64 {
    match kind {
        NdfKind::BlinnPhong => 1.0,
        NdfKind::Gaussian => 10.0,
        _ => MAX_ALPHA,
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// D ≥ 0 and finite for every accepted α and n·h in [0, 1]; the closed-form G1 (GGX,
    /// Beckmann) in [0, 1]; Smith and V-groove G2 in [0, 1] for consistent directions.
    #[test]
    fn model_terms_are_bounded(
        kind in prop::sample::select(NdfKind::ALL.to_vec()),
        a in alpha(),
        cos_h in 0.0f64..=1.0,
        tv in 0.0f64..std::f64::consts::FRAC_PI_2,
        tl in 0.0f64..std::f64::consts::FRAC_PI_2,
        phi in 0.0f64..std::f64::consts::PI,
    ) {
        let ndf = match Ndf::new(kind, a) {
            Ok(n) => n,
            Err(e) => {
                // only the NDF's own, documented limit may refuse an α in the range
                prop_assert!(a > own_limit(kind), "{:?} refused alpha {}: {}", kind, a, e);
                return Ok(());
            }
        };
        let d = ndf.d(cos_h);
        prop_assert!(d.is_finite() && d >= 0.0, "{:?} a={} D({})={}", kind, a, cos_h, d);
        if matches!(kind, NdfKind::Ggx | NdfKind::Beckmann) {
            for mu in [tv.cos(), tl.cos()] {
                let g = ndf.g1(mu);
                prop_assert!(g.is_finite() && (0.0..=1.0).contains(&g), "{:?} a={} G1({})={}", kind, a, mu, g);
            }
            // v = (sin tv, 0, cos tv), l = (sin tl cos phi, sin tl sin phi, cos tl), h ∝ v + l
            let v = [tv.sin(), 0.0, tv.cos()];
            let l = [tl.sin() * phi.cos(), tl.sin() * phi.sin(), tl.cos()];
            let s = [v[0] + l[0], v[1] + l[1], v[2] + l[2]];
            let len = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            if len > 1e-9 {
                let h = [s[0] / len, s[1] / len, s[2] / len];
                let vh = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
                for m in [Masking::SmithSeparable, Masking::SmithHeightCorrelated, Masking::VGroove] {
                    let g = m.g(&ndf, v[2], l[2], h[2], vh);
                    prop_assert!(g.is_finite() && (0.0..=1.0).contains(&g),
                        "{:?} {:?} a={} G2={}", kind, m, a, g);
                }
            }
        }
    }
}

/// A table's sidecar bytes and its other files (name, bytes).
type Outputs = (Vec<u8>, Vec<(String, Vec<u8>)>);

/// A real table's outputs, baked once.
fn baked_outputs() -> &'static Outputs {
    static OUT: std::sync::OnceLock<Outputs> = std::sync::OnceLock::new();
    OUT.get_or_init(|| {
        let text = r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "e", "kind": "albedo",
            "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
            "formats": ["exr", "ktx2", "h"],
            "axes": {"cos_theta_v": {"size": 5}, "roughness": {"size": 3, "quantity": "alpha"}}}]}"#;
        let p = preset::parse(text, "p.json", "p").unwrap();
        let (_, files) = brdfbake::pipeline::bake_preset(&p, std::path::Path::new("out"), None).unwrap();
        let mut sidecar = Vec::new();
        let mut others = Vec::new();
        for (path, bytes) in files {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if name.ends_with(".json") {
                sidecar = bytes;
            } else {
                others.push((name, bytes));
            }
        }
        (sidecar, others)
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Any single changed byte of a sealed sidecar breaks its seal (`bake --check`,
    /// `inspect`, `probe` and `verify` refuse it), and any changed byte of a file it lists
    /// breaks that file's digest.
    #[test]
    fn any_changed_byte_is_found(pos in any::<prop::sample::Index>(), x in 1u8..=255, which in 0usize..4) {
        let (sidecar, files) = baked_outputs();
        prop_assert_eq!(brdfbake::digest::check_seal(sidecar), Ok(()));
        let v: Value = serde_json::from_slice(sidecar).unwrap();
        if which == 0 {
            let mut bad = sidecar.clone();
            let i = pos.index(bad.len());
            bad[i] ^= x;
            prop_assert!(brdfbake::digest::check_seal(&bad).is_err(), "byte {} ^ {:#x}", i, x);
        } else {
            let (name, bytes) = &files[(which - 1) % files.len()];
            prop_assert_eq!(brdfbake::digest::check_file(&v, name, bytes), Ok(()));
            let mut bad = bytes.clone();
            let i = pos.index(bad.len());
            bad[i] ^= x;
            prop_assert!(brdfbake::digest::check_file(&v, name, &bad).is_err(), "{} byte {} ^ {:#x}", name, i, x);
        }
    }
}
