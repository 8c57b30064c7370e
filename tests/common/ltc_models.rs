//! The models the `ltc` kind accepts, by name and the preset's `model` object: judged by
//! tests/ltc_models.rs and measured by examples/ltc_models_check.rs on the same list.

/// The models: a name and the preset's `model`.
pub const MODELS: [(&str, &str); 7] = [
    (
        "ggx-hc",
        r#"{ "ndf": "ggx", "masking": "smith-height-correlated" }"#,
    ),
    (
        "ggx-separable",
        r#"{ "ndf": "ggx", "masking": "smith-separable" }"#,
    ),
    (
        "beckmann",
        r#"{ "ndf": "beckmann", "masking": "smith-height-correlated" }"#,
    ),
    (
        "charlie-ashikhmin",
        r#"{ "ndf": "charlie", "masking": "ashikhmin" }"#,
    ),
    (
        "charlie-conty-kulla",
        r#"{ "ndf": "charlie", "masking": "conty-kulla" }"#,
    ),
    ("lambert", r#"{ "diffuse": 1 }"#),
    ("burley", r#"{ "diffuse": 1, "diffuse_model": "burley" }"#),
];
