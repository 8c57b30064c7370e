//! The preset field `engine`: validated like every field, in the input hash only when set,
//! recorded in the sidecar (and read back from it), and `bake` warns about what does not work
//! in that engine (docs/engines.md), on stderr and in `--json`, with the formats as written.

#[path = "common/cli.rs"]
mod cli;

use brdfbake::engine::{warnings, Engine};
use brdfbake::preset::{parse, PresetTable};
use serde_json::Value;

fn preset(extra: &str, axes: &str, kind: &str) -> String {
    let model = if kind == "dfg" {
        r#""layout": "karis", "model": {"ndf": "ggx", "masking": "smith-height-correlated"}"#
    } else {
        r#""model": {"ndf": "ggx", "masking": "smith-height-correlated"}"#
    };
    format!(
        r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "t", "kind": "{kind}", {model},
           "axes": {axes}{extra}}}]}}"#
    )
}

const DFG_AXES: &str =
    r#"{"cos_theta_v": {"size": 8}, "roughness": {"size": 8, "quantity": "perceptual"}}"#;
const G2_AXES: &str = r#"{"cos_theta_v": {"size": 4}, "cos_theta_l": {"size": 4}, "roughness": {"size": 4, "quantity": "alpha", "range": [0.1, 1]}}"#;
const AVG_AXES: &str = r#"{"roughness": {"size": 8, "quantity": "perceptual"}}"#;

fn table(extra: &str, axes: &str, kind: &str) -> PresetTable {
    let text = preset(extra, axes, kind);
    parse(&text, "test", "test")
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .tables
        .remove(0)
}

#[test]
fn engine_is_validated_like_every_field() {
    for (value, expect) in [
        (r#""three""#, "unknown variant `three`"),
        (
            r#"1"#,
            "accepted names (a string, see docs/presets.md), got a number",
        ),
        (r#""""#, "unknown variant"),
    ] {
        let text = preset(&format!(r#", "engine": {value}"#), DFG_AXES, "dfg");
        let e = parse(&text, "test", "test").unwrap_err().to_string();
        assert!(e.contains("tables[0].engine"), "{e}");
        assert!(e.contains(expect), "{e}");
        if value != "1" {
            for name in Engine::ALL.map(|e| e.name()) {
                assert!(e.contains(name), "the accepted values are listed: {e}");
            }
        }
    }
    for e in Engine::ALL {
        let t = table(&format!(r#", "engine": "{}""#, e.name()), DFG_AXES, "dfg");
        assert_eq!(t.engine, Some(e));
    }
}

#[test]
fn engine_enters_the_input_hash_only_when_set() {
    let none = table("", DFG_AXES, "dfg");
    assert!(brdfbake::meta::inputs(&none).get("engine").is_none());
    let three = table(r#", "engine": "threejs""#, DFG_AXES, "dfg");
    let webgpu = table(r#", "engine": "webgpu""#, DFG_AXES, "dfg");
    assert_eq!(brdfbake::meta::inputs(&three)["engine"], "threejs");
    let h = |t: &PresetTable| brdfbake::meta::input_hash(t);
    assert_ne!(h(&none), h(&three));
    assert_ne!(h(&three), h(&webgpu));
    // a table without the field hashes its other inputs only: as before the field existed
    let mut back = three.clone();
    back.engine = None;
    assert_eq!(h(&back), h(&none));
}

/// Every warning rule, and where none applies.
#[test]
fn warnings_name_what_does_not_work() {
    let w = |extra: &str, axes: &str, kind: &str| warnings(&table(extra, axes, kind)).join("\n");
    let array = r#", "formats": ["ktx2"], "layout_3d": "array", "storage": "f16""#;
    let cases: &[(&str, &str, &str, &str, &[&str])] = &[
        // (engine, extra fields, axes, kind, expected fragments; none: no warning)
        (
            "threejs",
            array,
            G2_AXES,
            "g2",
            &["first layer", "layout_3d"],
        ),
        (
            "threejs",
            r#", "formats": ["ktx2"], "storage": "f16""#,
            G2_AXES,
            "g2",
            &[],
        ),
        (
            "threejs",
            r#", "formats": ["ktx2"]"#,
            DFG_AXES,
            "dfg",
            &["OES_texture_float_linear"],
        ),
        (
            "webgpu",
            r#", "formats": ["ktx2"]"#,
            DFG_AXES,
            "dfg",
            &["float32-filterable"],
        ),
        (
            "webgpu",
            r#", "formats": ["ktx2"], "storage": "f16""#,
            DFG_AXES,
            "dfg",
            &[],
        ),
        (
            "bevy",
            r#", "formats": ["ktx2"], "storage": "f16""#,
            AVG_AXES,
            "albedo-avg",
            &["1D texture", "D2"],
        ),
        (
            "bevy",
            r#", "formats": ["ktx2"]"#,
            DFG_AXES,
            "dfg",
            &["FLOAT32_FILTERABLE"],
        ),
        (
            "unreal",
            r#", "formats": ["ktx2"]"#,
            DFG_AXES,
            "dfg",
            &["no KTX2", "exr"],
        ),
        ("unreal", r#", "formats": ["exr"]"#, DFG_AXES, "dfg", &[]),
        (
            "unity",
            r#", "formats": ["exr"]"#,
            DFG_AXES,
            "dfg",
            &["v = 1", "1 - v"],
        ),
        ("unity", r#", "formats": ["ktx2"]"#, DFG_AXES, "dfg", &[]),
        (
            "godot",
            r#", "formats": ["ktx2"]"#,
            G2_AXES,
            "g2",
            &["2D textures only"],
        ),
        (
            "godot",
            r#", "formats": ["exr"]"#,
            DFG_AXES,
            "dfg",
            &["named A, B", "KTX2"],
        ),
        ("godot", r#", "formats": ["ktx2"]"#, DFG_AXES, "dfg", &[]),
        ("filament", r#", "formats": ["ktx2"]"#, G2_AXES, "g2", &[]),
        (
            "blender",
            r#", "formats": ["exr"]"#,
            G2_AXES,
            "g2",
            &["2D images only"],
        ),
        (
            "blender",
            r#", "formats": ["ktx2"]"#,
            DFG_AXES,
            "dfg",
            &["no KTX2"],
        ),
        // normalized-integer storage and png-data (docs/engines.md; the three.js and WebGPU
        // facts are checked in the browser by tests/gpu_path.rs)
        (
            "threejs",
            r#", "formats": ["ktx2"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &["EXT_texture_norm16", "R16G16_UNORM", "Unsupported vkFormat"],
        ),
        (
            "threejs",
            r#", "formats": ["ktx2"], "storage": "unorm16", "channels": ["A", "B", "0"]"#,
            DFG_AXES,
            "dfg",
            &["EXT_texture_norm16"],
        ),
        (
            "threejs",
            r#", "formats": ["ktx2"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &[],
        ),
        (
            "threejs",
            r#", "formats": ["png-data"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &["flipY", "8 bits"],
        ),
        (
            "webgpu",
            r#", "formats": ["ktx2"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &["texture-formats-tier1", "unfilterable-float"],
        ),
        (
            "webgpu",
            r#", "formats": ["ktx2"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &[],
        ),
        (
            "bevy",
            r#", "formats": ["ktx2"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &["TEXTURE_FORMAT_16BIT_NORM"],
        ),
        (
            "bevy",
            r#", "formats": ["png-data"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &["is_srgb: false"],
        ),
        (
            "unreal",
            r#", "formats": ["ktx2"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &["png-data", "no EXR"],
        ),
        (
            "unreal",
            r#", "formats": ["png-data"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &["sRGB off"],
        ),
        (
            "unity",
            r#", "formats": ["png-data"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &["1 - v", "sRGB (Color Texture)"],
        ),
        (
            "godot",
            r#", "formats": ["ktx2"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &["FORMAT_LA8", ".ra"],
        ),
        (
            "godot",
            r#", "formats": ["ktx2"], "storage": "unorm8", "channels": ["A", "B", "0"]"#,
            DFG_AXES,
            "dfg",
            &["R8G8B8A8_UNORM", "Unsupported format 37"],
        ),
        (
            "godot",
            r#", "formats": ["ktx2"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &[],
        ),
        (
            "godot",
            r#", "formats": ["png-data"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &["16-bit samples to 8 bits"],
        ),
        (
            "filament",
            r#", "formats": ["ktx2"], "storage": "unorm16""#,
            DFG_AXES,
            "dfg",
            &["no 16-bit normalized", "unorm8"],
        ),
        (
            "filament",
            r#", "formats": ["ktx2"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &[],
        ),
        (
            "blender",
            r#", "formats": ["ktx2"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &["png-data"],
        ),
        (
            "blender",
            r#", "formats": ["png-data"], "storage": "unorm8""#,
            DFG_AXES,
            "dfg",
            &["1 - v"],
        ),
    ];
    for (engine, extra, axes, kind, expect) in cases {
        let got = w(&format!(r#", "engine": "{engine}"{extra}"#), axes, kind);
        if expect.is_empty() {
            assert!(got.is_empty(), "{engine} {extra}: {got}");
        }
        for e in *expect {
            assert!(got.contains(e), "{engine} {extra}: {e:?} not in {got:?}");
        }
    }
    // the filament layout's channels R, G are what Godot's EXR loader maps
    let filament = preset(
        r#", "engine": "godot", "formats": ["exr"]"#,
        DFG_AXES,
        "dfg",
    )
    .replace("karis", "filament");
    let t = parse(&filament, "t", "t").unwrap().tables.remove(0);
    assert!(warnings(&t).is_empty(), "{:?}", warnings(&t));
    // without an engine: nothing
    assert!(warnings(&table(array, G2_AXES, "g2")).is_empty());
}

#[test]
fn bake_warns_and_the_sidecar_records_the_engine() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = preset(
        r#", "engine": "threejs", "formats": ["ktx2"], "layout_3d": "array""#,
        G2_AXES,
        "g2",
    );
    std::fs::write(d.join("p.json"), &text).unwrap();
    let o = cli::run(d, &["bake", "p.json", "--out", "out"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let err = cli::stderr(&o);
    assert!(
        err.contains("warning: p/t (engine threejs): three.js' KTX2Loader loads a 2D-array KTX2"),
        "{err}"
    );
    let side: Value =
        serde_json::from_slice(&std::fs::read(d.join("out/p/t.json")).unwrap()).unwrap();
    assert_eq!(side["engine"]["name"], "threejs");
    let ws = side["engine"]["warnings"].as_array().unwrap();
    assert_eq!(ws.len(), 2, "{ws:?}");
    assert!(ws[0].as_str().unwrap().contains("first layer"));
    // read back: the sidecar describes its input hash (bake --check, probe)
    let o = cli::run(d, &["bake", "p.json", "--out", "out", "--check"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let o = cli::run(
        d,
        &[
            "probe",
            "out/p/t.ktx2",
            "--at",
            "cos_theta_v=0.5,cos_theta_l=0.5,roughness=0.5",
            "--json",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let p: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(
        !p["notes"].to_string().contains("input_hash"),
        "{}",
        p["notes"]
    );
    // --quiet: no warnings; --json: in the document
    let o = cli::run(d, &["bake", "p.json", "--out", "out", "-q"]);
    assert!(cli::stderr(&o).is_empty(), "{}", cli::stderr(&o));
    let o = cli::run(d, &["bake", "p.json", "--out", "out", "--json"]);
    assert!(cli::stderr(&o).is_empty(), "{}", cli::stderr(&o));
    let j: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["tables"][0]["warnings"].as_array().unwrap().len(), 2);
    // the formats as written: --format exr drops the KTX2 array warning
    let o = cli::run(d, &["bake", "p.json", "--out", "out2", "--format", "exr"]);
    let err = cli::stderr(&o);
    assert!(!err.contains("first layer"), "{err}");
    assert!(err.contains("OES_texture_float_linear"), "{err}");
    let side: Value =
        serde_json::from_slice(&std::fs::read(d.join("out2/p/t.json")).unwrap()).unwrap();
    assert_eq!(side["engine"]["warnings"].as_array().unwrap().len(), 1);
    // without the field the sidecar has none
    std::fs::write(
        d.join("q.json"),
        preset(r#", "formats": ["ktx2"]"#, G2_AXES, "g2"),
    )
    .unwrap();
    let o = cli::run(d, &["bake", "q.json", "--out", "out"]);
    assert!(cli::stderr(&o).is_empty(), "{}", cli::stderr(&o));
    let side: Value =
        serde_json::from_slice(&std::fs::read(d.join("out/q/t.json")).unwrap()).unwrap();
    assert!(side.get("engine").is_none());
}

/// `bake --engine NAME` bakes every preset of that engine, the same files as naming them;
/// an unknown engine is exit 2 with the accepted names and nothing written.
#[test]
fn bake_by_engine_name() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = cli::run(d, &["bake", "--engine", "Three.js", "--out", "a", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let o = cli::run(
        d,
        &["bake", "threejs-dfg-lut", "threejs-ltc", "--out", "b", "-q"],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let (a, b) = (cli::snapshot(&d.join("a")), cli::snapshot(&d.join("b")));
    assert!(a.len() >= 4, "{:?}", a.keys());
    assert_eq!(
        a, b,
        "--engine three.js bakes what naming its presets bakes"
    );
    // a preset named and its engine's: each once
    let o = cli::run(
        d,
        &[
            "bake",
            "threejs-ltc",
            "--engine",
            "threejs",
            "--out",
            "c",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    assert_eq!(cli::snapshot(&d.join("c")), a);
    let o = cli::run(d, &["bake", "--engine", "godt", "--out", "e"]);
    cli::assert_fails(
        &o,
        2,
        &[
            "--engine \"godt\"",
            "Did you mean `godot`?",
            "blender",
            "threejs",
        ],
        "an unknown engine",
    );
    assert!(
        !d.join("e").exists(),
        "nothing written for an unknown engine"
    );
}
