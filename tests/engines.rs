//! Engine presets against the tables engines ship (`brdfbake compare`, src/engines/): each
//! preset bakes a shipped table on the engine's own grid, and the comparison texel by texel
//! must agree within the shipped table's own precision plus its noise — which only holds
//! when the layout (axes, texel positions, clamps, axis order, channels) is the engine's.
//! Each test also shows that a wrong layout fails the same comparison (a negative control),
//! and that the defects the comparison reports are the known ones.
//!
//! Data: tests/data/engines/ (README there: sources, commits, licences); EEVEE's GPL values
//! are quoted in tests/data/engines/eevee/ (quotes files `brdfbake compare` reads).

#[path = "common/cli.rs"]
mod cli;

use brdfbake::lut::Lut;
use brdfbake::preset::PresetTable;
use cli::run;
use serde_json::Value;
use std::path::Path;

fn data(p: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/engines")
        .join(p)
}

fn compare_json(args: &[&str]) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let o = run(dir.path(), &[&["compare"], args, &["--json"]].concat());
    assert!(o.status.success(), "{}", cli::stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

fn channel<'a>(doc: &'a Value, name: &str) -> &'a Value {
    doc["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["channel"] == name)
        .unwrap_or_else(|| panic!("no channel {name}: {doc}"))
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The `sigma` of a channel's noise finding.
fn sigma(c: &Value) -> f64 {
    c["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|x| x["kind"] == "noise")
        .map(|x| f(&x["sigma"]))
        .expect("a noise finding")
}

/// A built-in engine preset's one table, optionally with its JSON text edited first.
fn engine_table(name: &str, edit: impl Fn(String) -> String) -> PresetTable {
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == name)
        .unwrap_or_else(|| panic!("no engine preset {name}"));
    brdfbake::preset::parse(&edit(text.to_string()), name, name)
        .unwrap()
        .tables
        .remove(0)
}

fn stored(t: &PresetTable) -> Lut {
    t.stored(brdfbake::table::bake(&t.spec).unwrap())
}

/// Cycles' table_ggx_E is printed with 6 decimals (±5e-7) from 2^23 Owen-scrambled Sobol
/// samples per texel. brdfbake's table on Cycles' grid (roughness along u, endpoints clamped
/// to 1e-4) agrees to the printing plus the table's own texel-to-texel scatter (5σ, σ
/// estimated by `compare` from the second differences of the error); on a texel-centre grid
/// it disagrees by orders of magnitude more.
#[test]
fn cycles_ggx_e_and_eavg_agree_to_their_printed_precision() {
    let tables = data("cycles/shader.tables");
    let file = tables.to_str().unwrap();
    for (preset, ch) in [("cycles-ggx-e", "E"), ("cycles-ggx-eavg", "E_avg")] {
        let doc = compare_json(&[preset, file]);
        let c = channel(&doc, ch);
        let bound = 5e-7 + 5.0 * sigma(c);
        let max = f(&c["shipped"]["max_abs"]);
        assert!(
            max <= bound,
            "{preset}: Cycles' table is off by {max} (bound {bound}): {c}"
        );
        assert!(f(&c["brdfbake"]["max_rel"]) <= 1e-6, "{c}");
        assert_eq!(doc["brdfbake_within_bound"], true);
        // (brdfbake's error is measured against a separate, tighter bake)
        assert!(doc["reference_is_own_bake"].is_null(), "{doc}");
    }
    // the negative control: the same table at texel centres
    let dir = tempfile::tempdir().unwrap();
    let (_, text) = brdfbake::presets::ENGINES
        .iter()
        .find(|(n, _)| *n == "cycles-ggx-e")
        .unwrap();
    std::fs::write(
        dir.path().join("centres.json"),
        text.replace("\"convention\": \"endpoints\", ", ""),
    )
    .unwrap();
    let o = run(dir.path(), &["compare", "centres.json", file, "--json"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    let max = f(&channel(&doc, "E")["shipped"]["max_abs"]);
    assert!(
        max > 1e-2,
        "a texel-centre grid should not fit Cycles' table: {max}"
    );
}

/// three.js' DFGLUTData: half floats (2^-11 relative, ≤ 4.9e-4 below 1) from 4096 samples
/// per texel. Beyond its three most grazing rows (n·v ≥ 0.22) it agrees with brdfbake's
/// table on three.js' grid within f16 rounding plus 5σ of its own scatter; the comparison
/// names the grazing rows where its A channel is biased low (by up to 1.4e-2), and a
/// transposed layout fails.
#[test]
fn threejs_dfg_lut_agrees_but_for_its_grazing_rows() {
    let file = data("threejs/DFGLUTData.js");
    let doc = compare_json(&["threejs-dfg-lut", file.to_str().unwrap()]);
    let t = engine_table("threejs-dfg-lut", |s| s);
    let exact = stored(&t);
    let shipped = t
        .shipped
        .as_ref()
        .unwrap()
        .read(&std::fs::read(&file).unwrap(), [16, 16, 1], "three.js")
        .unwrap();
    for (c, name) in ["A", "B"].iter().enumerate() {
        let bound = 2f64.powi(-11) + 5.0 * sigma(channel(&doc, name));
        for j in 3..16 {
            for i in 0..16 {
                let s = shipped.values[(j * 16 + i) * 2 + c];
                let e = exact.texel([i, j, 0], c) as f64;
                assert!(
                    (s - e).abs() <= bound,
                    "{name} at roughness texel {i}, n.v texel {j}: three.js {s}, exact {e} (bound {bound})"
                );
            }
        }
    }
    // the grazing rows are named, and A there is low by more than 1e-2
    let a = channel(&doc, "A");
    let lines: Vec<&Value> = a["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|x| x["kind"] == "line" && x["axis"] == "cos_theta_v")
        .collect();
    assert!(
        lines.iter().any(|l| l["index"] == 0),
        "the n.v = 1/32 row is named: {a}"
    );
    assert!(f(&a["shipped"]["max_abs"]) > 1e-2 && f(&a["shipped"]["mean_signed"]) < 0.0);
    assert_eq!(a["shipped"]["worst_texel"][1], 0, "{a}");
    // the negative control: three.js' data read with n.v along u
    let swapped = engine_table("threejs-dfg-lut", |s| {
        s.replace("\"axis_order\": [\"roughness\", \"cos_theta_v\"],", "")
    });
    let exact = stored(&swapped);
    let worst = (0..256)
        .map(|t| (shipped.values[t * 2] - exact.data[t * 2] as f64).abs())
        .fold(0.0, f64::max);
    assert!(worst > 0.1, "a transposed layout should not fit: {worst}");
}

/// EEVEE's `bsdf_split_sum_ggx` texels quoted in `tests/data/engines/eevee/bsdf_split_sum_ggx.txt`
/// (GPL-2.0-or-later, Copyright Blender Authors): (row y, column x, A, B).
fn eevee_bsdf_split_sum() -> Vec<(usize, usize, f64, f64)> {
    std::fs::read_to_string(data("eevee/bsdf_split_sum_ggx.txt"))
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            (
                w[0].parse().unwrap(),
                w[1].parse().unwrap(),
                w[2].parse().unwrap(),
                w[3].parse().unwrap(),
            )
        })
        .collect()
}

/// EEVEE's generator averages 512² samples per texel with a float32 running sum. Once the
/// sum passes 2^17 its spacing is 2^-6, so each addition may round by 2^-7 and the mean by
/// up to N·2^-7/N = 2^-7 ≈ 7.8e-3 in the worst case; the quoted texels must agree with
/// brdfbake's table on EEVEE's grid (√(1 − cos θ) endpoints, cos θ clamped to [1e-4, 0.9999],
/// α = 0 in the first column) within that. In the α = 0 column every sample is the same
/// value, so the rounding does not average out: summing 512² copies of the exact term
/// (1 − (1 − μ)⁵, or (1 − μ)⁵) in float32, as the generator does, reproduces the shipped
/// values there, which differ from the exact ones by up to 3.4e-3 (A at y = 39) and 2.7e-3
/// (B at y = 62). A linear cos θ axis fails the comparison.
#[test]
fn eevee_bsdf_split_sum_agrees_and_its_alpha_zero_column_is_the_float32_sum() {
    let t = engine_table("eevee-bsdf-split-sum-ggx", |s| s);
    let ours = stored(&t);
    let bound = 2f64.powi(-7);
    let mut alpha_zero_worst: f64 = 0.0;
    for (y, x, a, b) in eevee_bsdf_split_sum() {
        let (oa, ob) = (
            ours.texel([x, y, 0], 0) as f64,
            ours.texel([x, y, 0], 1) as f64,
        );
        assert!(
            (oa - a).abs() <= bound && (ob - b).abs() <= bound,
            "texel x {x}, y {y}: EEVEE ({a}, {b}), brdfbake ({oa}, {ob}), bound {bound}"
        );
        if x == 0 {
            // the smooth limit, and EEVEE's float32 sum of N copies of it
            let mu = (1.0 - (y as f64 / 63.0).powi(2)).clamp(1e-4, 0.9999);
            let fc = (1.0 - mu).powi(5);
            assert!((oa - (1.0 - fc)).abs() < 1e-6 && (ob - fc).abs() < 1e-6);
            let f32_mean = |term: f64| {
                let n = 512 * 512;
                let mut s = 0.0f32;
                for _ in 0..n {
                    s += term as f32;
                }
                (s / n as f32) as f64
            };
            for (shipped, term) in [(a, 1.0 - fc), (b, fc)] {
                // (the quoted values have 6 decimals)
                assert!(
                    (f32_mean(term) - shipped).abs() <= 5e-6,
                    "y {y}: EEVEE's {shipped} is not the float32 mean {} of {term}",
                    f32_mean(term)
                );
                alpha_zero_worst = alpha_zero_worst.max((shipped - term).abs());
            }
        }
    }
    assert!(
        alpha_zero_worst > 2.5e-3,
        "the alpha = 0 column's known error: {alpha_zero_worst}"
    );
    // the negative control: the same table with cos theta linear along the axis
    let linear = engine_table("eevee-bsdf-split-sum-ggx", |s| {
        s.replace("\"warp\": \"sqrt-one-minus\", ", "")
    });
    let lin = stored(&linear);
    let worst = eevee_bsdf_split_sum()
        .into_iter()
        .map(|(y, x, a, _)| (lin.texel([x, y, 0], 0) as f64 - a).abs())
        .fold(0.0, f64::max);
    assert!(
        worst > 5.0 * bound,
        "a linear cos theta axis should not fit: {worst}"
    );
}

/// `compare` reads the formats engines ship and names what is wrong with a file: a shipped
/// table one row off (as Filament's cmgen writes its dfg.inc) shows as a shifted grid, a
/// wrong size or array name is a named error (exit 2), and a preset without `shipped` is
/// refused.
#[test]
fn compare_names_shifts_and_bad_files() {
    let dir = tempfile::tempdir().unwrap();
    let w = dir.path();
    // brdfbake's own Filament table, written as cmgen writes dfg.inc (half-float bits,
    // R, G, B per texel) but with every row holding the next row's values
    let t = {
        let text = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("presets/filament-dfg.json"),
        )
        .unwrap()
        .replace("\"size\": 128", "\"size\": 32");
        std::fs::write(w.join("filament.json"), &text).unwrap();
        brdfbake::preset::parse(&text, "f", "filament")
            .unwrap()
            .tables
            .remove(0)
    };
    let l = stored(&t);
    let mut inc = String::new();
    for y in 0..32 {
        for x in 0..32 {
            for c in 0..3 {
                let v = l.texel([x, (y + 1).min(31), 0], c);
                inc.push_str(&format!("0x{:04x}, ", half::f16::from_f32(v).to_bits()));
            }
        }
        inc.push('\n');
    }
    std::fs::write(w.join("dfg.inc"), &inc).unwrap();
    let o = run(w, &["compare", "filament.json", "dfg.inc", "--json"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    let g = channel(&doc, "G");
    assert!(
        g["findings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|x| x["kind"] == "shifted" && x["axis"] == "roughness" && x["by"] == 1),
        "{g}"
    );
    let o = run(w, &["compare", "filament.json", "dfg.inc"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("one texel off along roughness"), "{text}");

    // a file of the wrong size, a missing array, no shipped description, no such file
    std::fs::write(w.join("short.inc"), "0x3c00, 0x3c00").unwrap();
    let o = run(w, &["compare", "filament.json", "short.inc"]);
    cli::assert_fails(&o, cli::INPUT, &["short.inc", "2 values", "3072"], "short");
    let o = run(
        w,
        &[
            "compare",
            "cycles-ggx-e",
            data("threejs/DFGLUTData.js").to_str().unwrap(),
        ],
    );
    cli::assert_fails(
        &o,
        cli::INPUT,
        &["no array named \"table_ggx_E\""],
        "symbol",
    );
    let o = run(w, &["compare", "karis-envbrdf", "dfg.inc"]);
    cli::assert_fails(
        &o,
        cli::INPUT,
        &["no `shipped` description"],
        "plain preset",
    );
    let o = run(w, &["compare", "filament.json", "missing.inc"]);
    cli::assert_fails(&o, cli::INPUT, &["missing.inc", "no such file"], "missing");
}

/// `report --compare PRESET=FILE` adds a section per engine table: its source, the errors
/// per channel, the findings and a heatmap per channel.
#[test]
fn report_shows_engine_comparisons() {
    let dir = tempfile::tempdir().unwrap();
    let arg = format!(
        "threejs-dfg-lut={}",
        data("threejs/DFGLUTData.js").display()
    );
    let o = run(
        dir.path(),
        &["report", "energy-albedo", "--compare", &arg, "--out", "rep"],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let html = std::fs::read_to_string(dir.path().join("rep/index.html")).unwrap();
    let s = &html[html.find("<h2>Engine tables</h2>").expect("the section")..];
    assert!(s.contains("threejs-dfg-lut / dfg") && s.contains("mrdoob/three.js"));
    assert!(s.contains("cos_theta_v = 0.03125 (texel 0) errs more than the rest"));
    assert_eq!(
        s.matches("<title>dfg: shipped − exact").count(),
        2,
        "a heatmap per channel"
    );
    let o = run(
        dir.path(),
        &["report", "--compare", "threejs-dfg-lut", "--out", "rep"],
    );
    cli::assert_fails(&o, cli::INPUT, &["--compare", "PRESET=FILE"], "no file");
}

/// The glTF Sample Viewer's lut_ggx.png: 8 bits (half a step, 1/510) from 1024 Hammersley
/// samples per texel. Its B (green) agrees with brdfbake's table on the viewer's grid within
/// half a step plus 5σ of the PNG's own texel-to-texel scatter where n·v ≥ 0.01; its A (red) only
/// where n·v ≥ 0.19 (texel 192 on): at grazing views the 1024-sample estimate is biased low, by
/// up to ~2e-2 (measured; it is the finding the comparison names). A vertically flipped PNG
/// fits nowhere.
#[test]
fn gltf_lut_ggx_agrees_away_from_grazing_views() {
    let png = data("gltf/lut_ggx.png");
    let doc = compare_json(&["gltf-lut-ggx", png.to_str().unwrap()]);
    let t = engine_table("gltf-lut-ggx", |s| s);
    let exact = stored(&t);
    let bytes = std::fs::read(&png).unwrap();
    let shipped = t
        .shipped
        .as_ref()
        .unwrap()
        .read(&bytes, [1024, 1024, 1], "lut_ggx.png")
        .unwrap();
    // (worst |error|, mean signed error) over the columns from `first` on, asserting the bound
    // when `strict`
    let check = |shipped: &brdfbake::engines::shipped::ShippedTable,
                 fc: usize,
                 name: &str,
                 first: usize,
                 strict: bool|
     -> (f64, f64) {
        let c = exact.channels.iter().position(|x| x.name == name).unwrap();
        let bound = 0.5 / 255.0 + 5.0 * sigma(channel(&doc, name));
        let (mut worst, mut sum, mut n): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for j in 0..1024 {
            for i in first..1024 {
                let s = shipped.values[(j * 1024 + i) * 3 + fc];
                let e = exact.texel([i, j, 0], c) as f64;
                worst = worst.max((s - e).abs());
                sum += s - e;
                n += 1.0;
                if strict {
                    assert!(
                        (s - e).abs() <= bound,
                        "{name} at n.v texel {i}, roughness texel {j}: PNG {s}, exact {e} (bound {bound})"
                    );
                }
            }
        }
        (worst, sum / n)
    };
    check(&shipped, 1, "G", 11, true);
    check(&shipped, 0, "R", 192, true);
    // the grazing bias of A is real and one-sided: several half steps, the PNG low
    let (worst, mean) = check(&shipped, 0, "R", 0, false);
    assert!(worst > 5.0 / 255.0, "A's grazing error {worst}");
    assert!(mean < 0.0, "A's mean signed error {mean}");
    // the grazing columns are named
    let r = channel(&doc, "R");
    assert!(
        r["findings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|x| x["kind"] == "line" && x["index"] == 0),
        "{r}"
    );
    // the negative control: the same PNG read bottom-up
    let mut flipped = t.shipped.clone().unwrap();
    flipped.flip_y = true;
    let f = flipped
        .read(&bytes, [1024, 1024, 1], "lut_ggx.png")
        .unwrap();
    assert!(
        check(&f, 1, "G", 0, false).0 > 0.3,
        "a flipped PNG should not fit"
    );
}

/// The glTF Sample Viewer's lut_charlie.png is not the sheen albedo its shader uses it as:
/// its generator multiplies by 2π where it should divide by its sampling density, and its
/// 8-bit target clamps the albedo (up to ~174 at grazing views of smooth sheen) to 1. The
/// comparison shows both: tens of thousands of texels saturated at 1, and a mean error far
/// above the PNG's half step where nothing saturates.
#[test]
fn gltf_lut_charlie_is_clamped_and_is_not_the_albedo() {
    let png = data("gltf/lut_charlie.png");
    let doc = compare_json(&["gltf-lut-charlie", png.to_str().unwrap()]);
    let b = channel(&doc, "B");
    let saturated = b["findings"]
        .as_array()
        .unwrap()
        .iter()
        .find(|x| x["kind"] == "saturated" && x["value"] == 1.0)
        .unwrap_or_else(|| panic!("no saturation found: {b}"));
    assert!(saturated["count"].as_u64().unwrap() > 10_000, "{saturated}");
    assert!(f(&b["shipped"]["max_abs"]) > 100.0, "{b}");
    assert!(f(&b["shipped"]["mean_abs"]) > 20.0 / 255.0, "{b}");
    assert_eq!(doc["brdfbake_within_bound"], true);
}

/// BSDL's energy tables are Monte Carlo means of 16,384 stratified samples of a weight in
/// [0, 1] (its `genluts`, run at build time; the values in tests/data/engines/bsdl/ were made
/// by building it, see the README there). A weight in [0, 1] has a variance of at most 1/4,
/// so a plain Monte Carlo mean of N = 16384 samples has a standard error of at most
/// 1/(2√N) = 1/256 (stratification only lowers it): every texel lies within 5 of those of the
/// exact value, and the mean signed error over the table within 5 standard errors of the
/// observed scatter, σ/√(texels) — no bias.
const BSDL_MC_BOUND: f64 = 5.0 / 256.0;

/// The texels of a shipped text table with their exact values at the preset's grid.
fn shipped_and_exact(
    preset: &str,
    file: &str,
    edit: impl Fn(String) -> String,
) -> Vec<(usize, f64, f64)> {
    let t = engine_table(preset, edit);
    let exact = stored(&t);
    let bytes = std::fs::read(data(file)).unwrap();
    let [nx, ny] = [exact.axes[0].size, exact.axes[1].size];
    let s = t
        .shipped
        .as_ref()
        .unwrap()
        .read(&bytes, [nx, ny, 1], file)
        .unwrap();
    (0..nx * ny)
        .map(|k| {
            (
                k % nx,
                s.values[k],
                exact.texel([k % nx, k / nx, 0], 0) as f64,
            )
        })
        .collect()
}

/// BSDL's MiniMicrofacetGGX (1 − E of GGX, 16 × 16, μ = (i/15)² along u): within the Monte
/// Carlo bound everywhere and unbiased; read with a linear μ axis it is not.
#[test]
fn bsdl_ggx_energy_agrees_within_its_monte_carlo_error() {
    let file = "bsdl/MiniMicrofacetGGX.txt";
    let doc = compare_json(&["bsdl-ggx-energy", data(file).to_str().unwrap()]);
    let sigma = sigma(channel(&doc, "R"));
    let texels = shipped_and_exact("bsdl-ggx-energy", file, |s| s);
    let mut sum = 0.0;
    for &(i, s, e) in &texels {
        assert!(
            (s - e).abs() <= BSDL_MC_BOUND,
            "texel column {i}: BSDL {s}, exact {e}"
        );
        sum += s - e;
    }
    let mean = sum / texels.len() as f64;
    assert!(
        mean.abs() <= 5.0 * sigma / (texels.len() as f64).sqrt(),
        "mean signed error {mean}, scatter {sigma}"
    );
    let linear = shipped_and_exact("bsdl-ggx-energy", file, |s| {
        s.replace("\"warp\": \"sqrt\", ", "")
    });
    let worst = linear
        .iter()
        .map(|&(_, s, e)| (s - e).abs())
        .fold(0.0, f64::max);
    assert!(
        worst > 2.0 * BSDL_MC_BOUND,
        "a linear mu axis should not fit: {worst}"
    );
}

/// BSDL's ContyKullaSheen (1 − E of Charlie with the softened Conty–Kulla Λ, Charlie's
/// parameter itself along v): within the Monte Carlo bound away from its first column. At
/// μ = 10⁻⁶ BSDL's estimate is E = 0 and it stores 1 − min(E, 1) = 1, where the exact albedo
/// is near or above 1 (above it for most roughnesses: the fitted Λ does not conserve
/// energy, so 1 − E < 0): the comparison names the column and the 16 saturated texels. Read
/// with α = r² along v, the table does not fit.
#[test]
fn bsdl_sheen_energy_agrees_but_for_its_grazing_column() {
    let file = "bsdl/ContyKullaSheen.txt";
    let doc = compare_json(&["bsdl-sheen-energy", data(file).to_str().unwrap()]);
    let texels = shipped_and_exact("bsdl-sheen-energy", file, |s| s);
    let mut above_one = 0;
    for &(i, s, e) in &texels {
        if i == 0 {
            assert!(s == 1.0 && e < 0.01, "grazing column: BSDL {s}, exact {e}");
            above_one += usize::from(e < 0.0);
        } else {
            assert!(
                (s - e).abs() <= BSDL_MC_BOUND,
                "texel column {i}: BSDL {s}, exact {e}"
            );
        }
    }
    assert!(above_one > 8, "E > 1 at {above_one} of 16 grazing texels");
    let findings = channel(&doc, "R")["findings"].as_array().unwrap();
    assert!(findings
        .iter()
        .any(|x| x["kind"] == "line" && x["axis"] == "cos_theta_v" && x["index"] == 0));
    assert!(findings
        .iter()
        .any(|x| x["kind"] == "saturated" && x["value"] == 1.0 && x["count"] == 16));
    let squared = shipped_and_exact("bsdl-sheen-energy", file, |s| {
        s.replace("\"quantity\": \"alpha\"", "\"quantity\": \"perceptual\"")
    });
    let worst = squared
        .iter()
        .filter(|t| t.0 > 0)
        .map(|&(_, s, e)| (s - e).abs())
        .fold(0.0, f64::max);
    assert!(
        worst > 2.0 * BSDL_MC_BOUND,
        "alpha = r^2 should not fit: {worst}"
    );
}

/// The glTF Sample Viewer's lut_sheen_E.png is not computed by the viewer's tools: it is
/// Enterprise PBR's 16 × 16 Monte Carlo table of the sheen albedo (Charlie with Conty–Kulla's
/// Λ, α = max(r², 0.07)) enlarged to 1024² by a cubic B-spline and stored sRGB-encoded (the
/// preset's `source`; docs/engines.md). brdfbake's texels are exact; the PNG's differ by the
/// source's Monte Carlo noise and the B-spline's smoothing of its 16-sample grid. On a 32 × 32
/// spread of texels away from the grazing columns (n·v ≥ 1/16, where a 1/16 grid cannot follow
/// E's rise), the PNG decoded from sRGB agrees on average within `SHEEN_E_MEAN` (the 16 × 16
/// source's own rms error against exact values, 1.9e-3, measured with `compare` on a 16 × 16
/// preset: a positive, normalized filter does not raise a mean error above the largest
/// local error it averages, and curvature smoothing over h = 1/16 adds ~h²E''/6 < 5e-4
/// where E'' < 0.8). Read without the sRGB decode, or with α down to 0 (no clamp), it does not.
#[test]
fn gltf_lut_sheen_e_is_a_smoothed_enterprise_pbr_table() {
    const SHEEN_E_MEAN: f64 = 1.9e-3 + 5e-4;
    let t = engine_table("gltf-lut-sheen-e", |s| s);
    let bytes = std::fs::read(data("gltf/lut_sheen_E.png")).unwrap();
    let sh = t.shipped.clone().unwrap();
    let png = sh.read(&bytes, [1024, 1024, 1], "lut_sheen_E.png").unwrap();
    let mut raw = sh.clone();
    raw.decode = Default::default();
    let raw = raw
        .read(&bytes, [1024, 1024, 1], "lut_sheen_E.png")
        .unwrap();
    let (ax, ay) = (&t.spec.axes[0], &t.spec.axes[1]);
    let e = |alpha: f64, mu: f64| {
        let brdf = brdfbake::model::Brdf {
            specular: Some(brdfbake::model::Specular {
                ndf: brdfbake::model::Ndf::new(brdfbake::model::NdfKind::Charlie, alpha).unwrap(),
                masking: brdfbake::model::Masking::ContyKulla,
                fresnel: brdfbake::model::Fresnel::None,
            }),
            diffuse_weight: 0.0,
            diffuse: brdfbake::model::DiffuseLobe::Lambert,
        };
        brdfbake::table::albedo::directional_albedo(&brdf, mu, 1e-8).0[0]
    };
    let (mut sum, mut sum_raw, mut n, mut worst_unclamped): (f64, f64, f64, f64) =
        (0.0, 0.0, 0.0, 0.0);
    for j in (0..1024).step_by(32).map(|j| j + 16) {
        for i in (192..1024).step_by(26) {
            let (mu, alpha) = (ax.coord(i), ay.alpha(j).unwrap());
            let exact = e(alpha, mu);
            let k = (j * 1024 + i) * 3;
            sum += (png.values[k] - exact).abs();
            sum_raw += (raw.values[k] - exact).abs();
            n += 1.0;
            let r = (j as f64 + 0.5) / 1024.0;
            if r * r < 0.07 {
                worst_unclamped = worst_unclamped.max((png.values[k] - e(r * r, mu)).abs());
            }
        }
    }
    let (mean, mean_raw) = (sum / n, sum_raw / n);
    assert!(mean <= SHEEN_E_MEAN, "mean |error| {mean}");
    assert!(
        mean_raw > 10.0 * SHEEN_E_MEAN,
        "read without sRGB decoding: {mean_raw}"
    );
    assert!(
        worst_unclamped > 0.1,
        "alpha = r^2 below 0.07: {worst_unclamped}"
    );
}
