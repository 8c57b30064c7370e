//! Reliability, round three: inputs that used to be accepted and now are refused with a
//! message naming what was wrong, exit 2 and nothing written. Every input is made here.

use std::fs;
use std::path::Path;

#[path = "common/cli.rs"]
mod cli;
use cli::{assert_fails, run, INPUT};

/// An 8-bit RGB PNG of `w` × `h` pixels.
fn png(w: u32, h: u32) -> Vec<u8> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut wr = enc.write_header().unwrap();
    let data: Vec<u8> = (0..w * h * 3).map(|i| (i * 37 % 251) as u8).collect();
    wr.write_image_data(&data).unwrap();
    wr.finish().unwrap();
    out
}

/// glTF's lut_ggx preset at `n` × `n`.
fn gltf_ggx(n: usize) -> String {
    let text = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/presets/engines/gltf-lut-ggx.json"
    ))
    .unwrap();
    text.replace("\"size\": 1024", &format!("\"size\": {n}"))
}

/// A shipped file of another size than the preset's table is refused, naming both sizes:
/// a PNG of the same pixel count in another shape, a PNG one row and column larger or
/// smaller, a text table with numbers appended or missing.
#[test]
fn compare_refuses_a_file_of_another_size() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("ggx8.json"), gltf_ggx(8)).unwrap();
    for (w, h, expect) in [
        (16, 4, "16 × 4 pixels"),
        (9, 9, "9 × 9 pixels"),
        (7, 7, "7 × 7 pixels"),
    ] {
        fs::write(d.join("lut.png"), png(w, h)).unwrap();
        let o = run(d, &["compare", "ggx8.json", "lut.png"]);
        assert_fails(&o, INPUT, &[expect, "8 × 8 texels"], &format!("{w}x{h}"));
    }
    fs::write(d.join("lut.png"), png(8, 8)).unwrap();
    let o = run(d, &["compare", "ggx8.json", "lut.png"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));

    // BSDL's 16 × 16 text table, with two numbers appended and with one missing
    let bsdl = fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/engines/bsdl/MiniMicrofacetGGX.txt"
    ))
    .unwrap();
    let cases = [
        (
            format!("{bsdl}\n0.5 0.25\n"),
            "258 values where the table needs 256",
        ),
        (
            bsdl.trim_end()
                .rsplit_once(char::is_whitespace)
                .unwrap()
                .0
                .to_string(),
            "255 values where the table needs 256",
        ),
    ];
    for (text, expect) in cases {
        fs::write(d.join("bsdl.txt"), text).unwrap();
        let o = run(d, &["compare", "bsdl-ggx-energy", "bsdl.txt"]);
        assert_fails(&o, INPUT, &[expect], expect);
    }
    assert_no_outputs(d);
}

/// compare writes nothing: only the inputs made here are in the folder.
fn assert_no_outputs(d: &Path) {
    for e in fs::read_dir(d).unwrap() {
        let n = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(
            n.ends_with(".json") || n.ends_with(".png") || n.ends_with(".txt"),
            "{n}"
        );
    }
}

fn albedo_preset(roughness_range: &str) -> String {
    format!(
        r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "e", "kind": "albedo",
          "model": {{"ndf": "ggx", "masking": "smith-height-correlated"}},
          "axes": {{"cos_theta_v": {{"size": 8}},
                   "roughness": {{"size": 8, "quantity": "perceptual", "range": {roughness_range}}}}}}}]}}"#
    )
}

/// Negative roughness (a perceptual r squares to a positive alpha: a mirrored table) and a
/// range past alpha = 1 (which used to fail as a tolerance miss) are range errors; `eval`
/// refuses a negative roughness by its flag.
#[test]
fn roughness_out_of_range_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (range, shown) in [
        ("[-1, 0]", "got [-1, 0]"),
        ("[0, 2]", "got [0, 2]"),
        ("[-0.5, 0.5]", "got [-0.5, 0.5]"),
    ] {
        fs::write(d.join("r.json"), albedo_preset(range)).unwrap();
        let o = run(d, &["bake", "r.json", "--out", "out"]);
        assert_fails(
            &o,
            INPUT,
            &["axes.roughness.range", "within [0, 1]", shown],
            range,
        );
    }
    assert!(!d.join("out").exists());
    for args in [
        &["eval", "dfg", "--roughness=-1", "--cos-theta", "0.5"][..],
        &["eval", "dfg", "--roughness", "-0.25", "--cos-theta", "0.5"],
        &["eval", "dfg", "--alpha", "-0.1", "--cos-theta", "0.5"],
    ] {
        let o = run(d, args);
        assert_fails(&o, INPUT, &["is negative"], &format!("{args:?}"));
    }
}

/// Fields that used to be ignored are errors naming them: a model on a vgroove table, an
/// empty `symbol`, a shipped channel listed twice (named as the preset writes it).
#[test]
fn ignored_fields_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let vgroove = r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "g", "kind": "vgroove",
      "model": MODEL,
      "axes": {"n_dot_l": {"size": 4}, "n_dot_h": {"size": 4}, "n_dot_v": {"size": 4}}}]}"#;
    for (model, field) in [
        (r#"{"ndf": "ggx"}"#, "model.ndf"),
        (r#"{"masking": "smith-separable"}"#, "model.masking"),
        (
            r#"{"fresnel": {"type": "dielectric", "eta": 1.5}}"#,
            "model.fresnel",
        ),
    ] {
        fs::write(d.join("v.json"), vgroove.replace("MODEL", model)).unwrap();
        let o = run(d, &["bake", "v.json", "--out", "out"]);
        assert_fails(&o, INPUT, &[field, "V-groove masking alone"], model);
    }
    // the model the kind implies is accepted
    fs::write(
        d.join("v.json"),
        vgroove.replace("MODEL", r#"{"masking": "v-groove"}"#),
    )
    .unwrap();
    let o = run(d, &["bake", "v.json", "--out", "out", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));

    let root = env!("CARGO_MANIFEST_DIR");
    let edit = |preset: &str, f: &dyn Fn(&mut serde_json::Value)| {
        let mut v: serde_json::Value = serde_json::from_str(
            &fs::read_to_string(format!("{root}/presets/engines/{preset}.json")).unwrap(),
        )
        .unwrap();
        f(&mut v["tables"][0]["shipped"]);
        fs::write(d.join("e.json"), v.to_string()).unwrap();
    };
    edit("cycles-ggx-e", &|s| s["symbol"] = "".into());
    let o = run(
        d,
        &[
            "compare",
            "e.json",
            &format!("{root}/tests/data/engines/cycles/shader.tables"),
        ],
    );
    assert_fails(&o, INPUT, &["shipped", "symbol is empty"], "symbol");
    edit("bsdl-ggx-energy", &|s| {
        s["channels"] = serde_json::json!(["1-E", "1-E"])
    });
    let o = run(
        d,
        &[
            "compare",
            "e.json",
            &format!("{root}/tests/data/engines/bsdl/MiniMicrofacetGGX.txt"),
        ],
    );
    assert_fails(
        &o,
        INPUT,
        &["channels[1]: \"1-E\" is listed twice"],
        "channels",
    );
}

/// A texture whose sidecar path holds something other than a file (a FIFO, a link to a
/// device, a link loop) is refused, saying what was found, instead of read as having no
/// sidecar.
#[test]
fn a_sidecar_path_that_is_not_a_file_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = run(d, &["bake", "filament-dfg", "--out", "out", "-q"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    fs::copy(d.join("out/filament-dfg/dfg.exr"), d.join("x.exr")).unwrap();
    let side = d.join("x.json");
    let fifo = std::ffi::CString::new(side.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a NUL-terminated path
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0);
    let cases: [(&dyn Fn(), &str); 3] = [
        (&|| {}, "holds a FIFO"),
        (
            &|| {
                fs::remove_file(&side).unwrap();
                std::os::unix::fs::symlink("/dev/zero", &side).unwrap();
            },
            "holds a character device",
        ),
        (
            &|| {
                fs::remove_file(&side).unwrap();
                std::os::unix::fs::symlink("x.json", &side).unwrap();
            },
            "loops or leads nowhere",
        ),
    ];
    for (setup, expect) in cases {
        setup();
        for cmd in ["inspect", "verify", "probe"] {
            let mut args = vec![cmd, "x.exr"];
            if cmd == "probe" {
                args.extend(["--at", "cos_theta_v=0.5,roughness=0.5"]);
            }
            let o = cli::run_within(d, &args, std::time::Duration::from_secs(60));
            assert_fails(&o, INPUT, &["x.json", expect], &format!("{cmd}: {expect}"));
        }
    }
}

/// Control characters from a preset (ESC, BEL, NUL) reach the terminal escaped.
#[test]
fn control_characters_in_messages_are_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = "{\"schema\": \"brdfbake.preset/1\", \"tables\": [{\"name\": \"e\\u001b[31m\\u0007\\u0000\", \"kind\": \"no-such\\u001b]0;x\\u0007\"}]}";
    fs::write(d.join("c.json"), text).unwrap();
    let o = run(d, &["bake", "c.json", "--out", "out"]);
    let err = cli::stderr(&o);
    assert_eq!(o.status.code(), Some(INPUT), "{err}");
    assert!(
        !err.chars().any(|c| c.is_control() && c != '\n'),
        "raw control characters: {err:?}"
    );
    assert!(err.contains("\\u{1b}"), "{err}");
}

/// Writes `bytes` as `bad/<name>` beside a copy of `side` sealed over it (the digests
/// recomputed, as someone who edits a file and its sidecar together would).
fn sealed_copy(d: &Path, name: &str, bytes: &[u8], side: &serde_json::Value) {
    fs::create_dir_all(d.join("bad")).unwrap();
    fs::write(d.join("bad").join(name), bytes).unwrap();
    let json = name.rsplit_once('.').unwrap().0.to_string() + ".json";
    fs::write(
        d.join("bad").join(json),
        brdfbake::digest::seal(side.clone(), &[(name, bytes)]),
    )
    .unwrap();
}

/// A file whose structure contradicts its sidecar is refused whatever its digests say: every
/// 4-byte field of a KTX2 header and level index, bytes of its DFD and key/value data
/// (KTXorientation), bytes appended; every DDS header field; an EXR without its input-hash
/// attribute; a sidecar whose coordinates, α or channel names were edited. Each by `inspect`
/// and `verify`, exit 2.
#[test]
fn structure_that_contradicts_the_sidecar_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = run(
        d,
        &[
            "bake",
            "karis-envbrdf",
            "--format",
            "ktx2,dds,exr",
            "--out",
            "out",
            "-q",
        ],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let base = d.join("out/karis-envbrdf");
    let side: serde_json::Value =
        serde_json::from_slice(&fs::read(base.join("envbrdf.json")).unwrap()).unwrap();
    let refused = |name: &str, what: &str| {
        for cmd in ["inspect", "verify"] {
            let o = run(d, &[cmd, &format!("bad/{name}")]);
            assert_eq!(
                o.status.code(),
                Some(INPUT),
                "{cmd} {what}: {}",
                cli::stderr(&o)
            );
        }
    };
    // the unedited copy is accepted
    let ktx2 = fs::read(base.join("envbrdf.ktx2")).unwrap();
    sealed_copy(d, "envbrdf.ktx2", &ktx2, &side);
    let o = run(d, &["inspect", "bad/envbrdf.ktx2"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));

    let u = |b: &[u8], o: usize| u32::from_le_bytes(b[o..o + 4].try_into().unwrap()) as usize;
    let (dfd, kvd) = (u(&ktx2, 48), u(&ktx2, 56));
    let kvd_len = u(&ktx2, 60);
    let mut offsets: Vec<usize> = (12..104).step_by(4).collect();
    offsets.extend([dfd + 4, dfd + 12, dfd + 20, kvd + 6, kvd + kvd_len - 2]);
    for at in offsets {
        let mut b = ktx2.clone();
        b[at] ^= 0x01;
        sealed_copy(d, "envbrdf.ktx2", &b, &side);
        refused("envbrdf.ktx2", &format!("KTX2 byte {at}"));
    }
    let mut longer = ktx2.clone();
    longer.extend(std::iter::repeat_n(0u8, 100));
    sealed_copy(d, "envbrdf.ktx2", &longer, &side);
    refused("envbrdf.ktx2", "KTX2 with bytes appended");

    let dds = fs::read(base.join("envbrdf.dds")).unwrap();
    for at in (4..148).step_by(4) {
        let mut b = dds.clone();
        b[at] ^= 0x01;
        sealed_copy(d, "envbrdf.dds", &b, &side);
        refused("envbrdf.dds", &format!("DDS byte {at}"));
    }

    // an EXR of the same texels without the input-hash attribute
    let exr = fs::read(base.join("envbrdf.exr")).unwrap();
    let (w, h, planes, _) = brdfbake::encode::decode_exr(&exr).unwrap();
    let rb = brdfbake::readback::read(&base.join("envbrdf.exr")).unwrap();
    let lut = rb.lut.unwrap();
    assert_eq!(
        (w, h, planes.len()),
        (lut.dim(0), lut.dim(1), lut.channels.len())
    );
    use brdfbake::encode::Encoder;
    let bare = brdfbake::encode::ExrEncoder {
        storage: rb.table.unwrap().spec.storage,
        table_name: "envbrdf".into(),
    }
    .encode(&lut, &[])
    .unwrap();
    sealed_copy(d, "envbrdf.exr", &bare, &side);
    refused("envbrdf.exr", "EXR without brdfbake:input_hash");

    // sidecars edited where they describe the table: a coordinate, an alpha, a channel name
    for (pointer, value) in [
        ("/axes/0/coordinates/3", serde_json::json!(0.5)),
        ("/axes/1/alpha/5", serde_json::json!(0.25)),
        ("/channels/0/name", serde_json::json!("X")),
    ] {
        let mut s = side.clone();
        *s.pointer_mut(pointer)
            .unwrap_or_else(|| panic!("{pointer}")) = value;
        sealed_copy(d, "envbrdf.ktx2", &ktx2, &s);
        refused("envbrdf.ktx2", pointer);
    }
}

/// One rule for `null`: refused wherever it stands, naming the place, for required and
/// optional fields alike.
#[test]
fn null_is_refused_everywhere() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let base = r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "e", "kind": "albedo", TABLE
      "model": {"ndf": "ggx", "masking": "smith-height-correlated" MODEL},
      "axes": {"cos_theta_v": {"size": 8 AXIS}, "roughness": {"size": 8, "quantity": "perceptual"}}}]}"#;
    let fill = |t: &str, m: &str, a: &str| {
        base.replace("TABLE", t)
            .replace("MODEL", m)
            .replace("AXIS", a)
    };
    let mut cases = Vec::new();
    for f in [
        "storage",
        "tolerance",
        "formats",
        "scale",
        "channels",
        "axis_order",
        "accept_error_estimate",
        "engine",
        "ltc",
        "shipped",
        "layout_3d",
        "cloth",
    ] {
        cases.push((
            fill(&format!("\"{f}\": null,"), "", ""),
            format!("tables[0].{f}"),
        ));
    }
    for f in ["fresnel", "diffuse", "diffuse_model", "classic"] {
        cases.push((
            fill("", &format!(", \"{f}\": null"), ""),
            format!("tables[0].model.{f}"),
        ));
    }
    for f in ["range", "convention", "warp", "clamp", "quantity"] {
        cases.push((
            fill("", "", &format!(", \"{f}\": null")),
            format!("tables[0].axes.cos_theta_v.{f}"),
        ));
    }
    for (text, path) in cases {
        fs::write(d.join("n.json"), text).unwrap();
        let o = run(d, &["bake", "n.json", "--out", "out"]);
        assert_fails(&o, INPUT, &[&path, "is null"], &path);
    }
    assert!(!d.join("out").exists());
}
