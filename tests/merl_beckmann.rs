//! `measured` fits Beckmann + Lambert as well as GGX + Lambert: on a MERL file written in
//! the exact format from a known Beckmann + Lambert material (per channel kd, F0, α), the
//! Beckmann fit recovers the parameters, and the GGX fit of the same data is measurably
//! worse (its reported error is what tells the two apart).

use brdfbake::merl::{
    self, fit_beckmann_lambert, fit_cook_torrance_lambert, fit_ggx_lambert, Merl,
};
use brdfbake::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
use std::process::Command;

/// Known per-channel parameters (kd, F0, α).
const PARAMS: [(f64, f64, f64); 3] = [(0.25, 0.04, 0.15), (0.1, 0.6, 0.3), (0.0, 0.95, 0.6)];

fn model_with(c: usize, masking: Masking) -> Brdf {
    let (kd, f0, a) = PARAMS[c];
    Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Beckmann, a).unwrap(),
            masking,
            fresnel: Fresnel::Schlick { f0 },
        }),
        diffuse_weight: kd,
        diffuse: brdfbake::model::DiffuseLobe::Lambert,
    }
}

fn model(c: usize) -> Brdf {
    model_with(c, Masking::SmithHeightCorrelated)
}

fn bytes_with(masking: Masking) -> Vec<u8> {
    let m = [0, 1, 2].map(|c| model_with(c, masking));
    merl::write_bytes(|wi, wo| [m[0].eval(wo, wi), m[1].eval(wo, wi), m[2].eval(wo, wi)])
}

fn bytes() -> Vec<u8> {
    let m = [model(0), model(1), model(2)];
    merl::write_bytes(|wi, wo| [m[0].eval(wo, wi), m[1].eval(wo, wi), m[2].eval(wo, wi)])
}

/// The data are the Beckmann model at the nodes, so the weighted least squares has its
/// exact minimum (zero residual) at the true parameters: the golden-section search stops at
/// |Δ ln α| < 1e-10 and J is quadratic about the minimum, so α is found far better than
/// the 1e-6 relative asserted, and kd, F0 follow from the exact 2×2 solve at that α (their
/// error is of the order of α's, times the condition of the solve: 1e-6 absolute). The
/// GGX fit of the same data cannot reach zero residual: its relative rms is > 1e-3 (GGX's
/// tails differ from Beckmann's by far more), so the fit error tells the NDFs apart.
#[test]
fn beckmann_fit_recovers_parameters() {
    let m = Merl::parse(&bytes()).unwrap();
    for (c, &(kd, f0, a)) in PARAMS.iter().enumerate() {
        let f = fit_beckmann_lambert(&m, c, [3, 6]).unwrap();
        assert_eq!(f.ndf, "beckmann");
        assert!((f.alpha - a).abs() <= 1e-6 * a, "c{c}: {f:?}");
        assert!((f.kd - kd).abs() <= 1e-6, "c{c}: {f:?}");
        assert!((f.f0 - f0).abs() <= 1e-6, "c{c}: {f:?}");
        assert!(f.rel_rms <= 1e-6, "c{c}: {f:?}");
        assert!(f.nodes > 10_000 && !f.alpha_at_limit);
        let g = fit_ggx_lambert(&m, c, [3, 6]).unwrap();
        assert_eq!(g.ndf, "ggx");
        assert!(
            g.rel_rms > 1e-3 && g.rel_rms > 1e3 * f.rel_rms,
            "c{c}: ggx {g:?} vs beckmann {f:?}"
        );
    }
}

/// Cook & Torrance's model (Beckmann D, V-groove G, Schlick F) + Lambert, written as a MERL
/// file, is recovered by the Cook–Torrance fit for the same reason (exact data, exact
/// minimum; J is smooth in α because G does not depend on α); the Smith-Beckmann fit of the
/// same data cannot reach zero residual (relative rms > 1e-4: the two G differ at grazing
/// angles by far more).
#[test]
fn cook_torrance_fit_recovers_parameters() {
    let m = Merl::parse(&bytes_with(Masking::VGroove)).unwrap();
    for (c, &(kd, f0, a)) in PARAMS.iter().enumerate() {
        let f = fit_cook_torrance_lambert(&m, c, [3, 6]).unwrap();
        assert_eq!((f.ndf, f.masking), ("beckmann", "v-groove"));
        assert!((f.alpha - a).abs() <= 1e-6 * a, "c{c}: {f:?}");
        assert!((f.kd - kd).abs() <= 1e-6, "c{c}: {f:?}");
        assert!((f.f0 - f0).abs() <= 1e-6, "c{c}: {f:?}");
        assert!(f.rel_rms <= 1e-6, "c{c}: {f:?}");
        let b = fit_beckmann_lambert(&m, c, [3, 6]).unwrap();
        assert!(b.rel_rms > 1e-4, "c{c}: smith {b:?} vs v-groove {f:?}");
    }
}

/// The CLI reports both fits (`fit` GGX as before, `fit_beckmann`), writes the albedo as an
/// EXR + sidecar table with `--out` (nothing for a bad file), `--fit beckmann` fits only
/// that one, and an unknown `--fit` NDF is an input error naming what is accepted.
#[test]
fn cli_reports_the_beckmann_fit() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("beckmann.binary");
    std::fs::write(&file, bytes()).unwrap();
    let bin = env!("CARGO_BIN_EXE_brdfbake");
    let tables = dir.path().join("tables");
    let out = Command::new(bin)
        .args(["measured", "--albedo-size", "2", "--json", "--out"])
        .arg(&tables)
        .arg(&file)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let b = &v["fit_beckmann"]["channels"][1]["fit"];
    assert_eq!(b["ndf"], "beckmann");
    assert!((b["alpha"].as_f64().unwrap() - 0.3).abs() < 1e-6, "{b}");
    assert!(b["rel_rms"].as_f64().unwrap() <= 1e-6, "{b}");
    let g = &v["fit"]["channels"][1]["fit"];
    assert_eq!(g["ndf"], "ggx");
    assert!(g["rel_rms"].as_f64().unwrap() > 1e-3, "{g}");

    // --out wrote the albedo as a table: the EXR holds the reported albedo rows (f32
    // rounding, relative 2^-24), the sidecar says what it is
    let rb = brdfbake::readback::read(&tables.join("beckmann-albedo.exr")).unwrap();
    let lut = rb.lut.unwrap();
    assert_eq!(lut.axes[0].name, "cos_theta_v");
    let rows = v["albedo"]["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for (i, r) in rows.iter().enumerate() {
        for (c, name) in ["R", "G", "B"].into_iter().enumerate() {
            let e = r["albedo"][c].as_f64().unwrap();
            // without a preset table the channels come in the file's (alphabetical) order
            let k = lut.channels.iter().position(|ch| ch.name == name).unwrap();
            let stored = lut.texel([i, 0, 0], k) as f64;
            assert!(
                (stored - e).abs() <= 6e-8 * e.abs(),
                "{i} {c}: {stored} {e}"
            );
        }
    }
    let side = rb.sidecar.unwrap();
    assert_eq!(side["table"]["kind"], "measured-albedo");
    assert_eq!(side["model"]["fits"][1]["ndf"], "beckmann");
    // inspect reads it; verify says why it cannot recompute it (exit 2)
    let st = Command::new(bin)
        .arg("inspect")
        .arg(tables.join("beckmann-albedo.exr"))
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let st = Command::new(bin)
        .arg("verify")
        .arg(tables.join("beckmann-albedo.exr"))
        .output()
        .unwrap();
    assert_eq!(st.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&st.stderr).contains("measured --out"));
    // a truncated file writes nothing
    let bad = dir.path().join("short.binary");
    std::fs::write(&bad, &bytes()[..1000]).unwrap();
    let none = dir.path().join("none");
    let st = Command::new(bin)
        .args(["measured", "--out"])
        .arg(&none)
        .arg(&bad)
        .output()
        .unwrap();
    assert_eq!(st.status.code(), Some(2));
    assert!(!none.exists());

    let out = Command::new(bin)
        .args(["measured", "--albedo-size", "1", "--fit", "beckmann"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(text.matches("Beckmann + Lambert").count(), 3, "{text}");
    assert!(!text.contains("GGX"), "{text}");

    let out = Command::new(bin)
        .args(["measured", "--fit", "phong"])
        .arg(&file)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--fit")
            && err.contains("phong")
            && err.contains("ggx, beckmann, cook-torrance"),
        "{err}"
    );
}
