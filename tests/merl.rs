//! The MERL binary format: files written from analytic BRDFs in that exact layout (so what
//! they hold is known), read back, baked into albedo, fitted; unmeasured entries; every
//! kind of malformed file gives a clear error (exit code 2 from the CLI), never a panic.

use brdfbake::laws::directional_albedo;
use brdfbake::merl::{self, fit_ggx_lambert, Merl, MerlChannel, FILE_BYTES, N, SCALE};
use brdfbake::model::classic::{Dir, Reflectance};
use brdfbake::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
use std::process::Command;
use std::sync::{Arc, OnceLock};

/// Known per-channel parameters (kd, F0, α) of the synthetic material.
const PARAMS: [(f64, f64, f64); 3] = [(0.2, 0.04, 0.2), (0.3, 0.5, 0.35), (0.1, 0.9, 0.5)];

fn model(c: usize) -> Brdf {
    let (kd, f0, a) = PARAMS[c];
    Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, a).unwrap(),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::Schlick { f0 },
        }),
        diffuse_weight: kd,
        diffuse: brdfbake::model::DiffuseLobe::Lambert,
    }
}

/// The synthetic file, built once.
fn bytes() -> &'static Vec<u8> {
    static B: OnceLock<Vec<u8>> = OnceLock::new();
    B.get_or_init(|| {
        let m = [model(0), model(1), model(2)];
        merl::write_bytes(|wi, wo| [m[0].eval(wo, wi), m[1].eval(wo, wi), m[2].eval(wo, wi)])
    })
}

fn parsed() -> &'static Arc<Merl> {
    static M: OnceLock<Arc<Merl>> = OnceLock::new();
    M.get_or_init(|| Arc::new(Merl::parse(bytes()).unwrap()))
}

/// Number of nodes whose directions are below the horizon (written as unmeasured).
fn below_horizon_nodes() -> usize {
    let mut n = 0;
    for i in 0..90 {
        for j in 0..90 {
            for k in 0..180 {
                let (th, td, pd) = merl::node_angles(i, j, k);
                let (wi, wo) = merl::directions(th, td, pd);
                if wi[2] <= 0.0 || wo[2] <= 0.0 {
                    n += 1;
                }
            }
        }
    }
    n
}

/// The layout: header 90 90 180, size, per-channel scale, index order, and the node
/// convention (a node's directions map back to exactly its angles).
#[test]
fn layout_and_round_trip() {
    let b = bytes();
    assert_eq!(b.len(), FILE_BYTES);
    assert_eq!(b.len(), 12 + 3 * 90 * 90 * 180 * 8);
    assert_eq!(&b[0..4], &90i32.to_le_bytes());
    assert_eq!(&b[4..8], &90i32.to_le_bytes());
    assert_eq!(&b[8..12], &180i32.to_le_bytes());
    let m = parsed();
    let below = below_horizon_nodes();
    assert_eq!(m.unmeasured, [below; 3]);
    assert_eq!(m.unmeasured_above_horizon, [0; 3]);
    // a spread of nodes: raw stored value × scale = the model at the node's directions,
    // and the half/difference angles of those directions are the node's angles
    for &(i, j, k) in &[
        (0, 0, 0),
        (10, 20, 30),
        (45, 45, 90),
        (89, 3, 179),
        (60, 10, 5),
    ] {
        let (th, td, pd) = merl::node_angles(i, j, k);
        let (wi, wo) = merl::directions(th, td, pd);
        if wi[2] <= 0.0 || wo[2] <= 0.0 {
            continue;
        }
        let idx = merl::index(i, j, k);
        assert_eq!(idx, k + 180 * (j + 90 * i));
        for (c, &scale) in SCALE.iter().enumerate() {
            let at = 12 + (c * N + idx) * 8;
            let raw = f64::from_le_bytes(b[at..at + 8].try_into().unwrap());
            let truth = model(c).eval(wo, wi);
            // two roundings (÷ scale when writing, × scale when reading)
            assert!((raw * scale - truth).abs() <= 4.0 * f64::EPSILON * truth);
            assert!((m.values[c][idx] - truth).abs() <= 4.0 * f64::EPSILON * truth);
            // the interpolating reader at a node returns the node (weights ~1 there; the
            // angles round-trip to ~1e-15 rad, so allow 1e-9 relative)
            let e = m.eval(c, wi, wo).unwrap();
            assert!(
                (e - truth).abs() <= 1e-9 * truth.max(1e-3),
                "{i} {j} {k} c{c}: {e} {truth}"
            );
        }
        if j > 0 {
            let (a, b2, d) = merl::half_diff(wi, wo).unwrap();
            assert!((a - th).abs() < 1e-12 && (b2 - td).abs() < 1e-12);
            // at θh = 0 (h = n) φh is arbitrary and so is φd: only checked for θh > 0
            if i > 0 {
                assert!((d - pd).abs() < 1e-12, "{i} {j} {k}: {d} {pd}");
            }
        }
    }
}

/// The fit recovers the known (kd, F0, α) of every channel: the data are the model at the
/// nodes, so the weighted least squares has its exact minimum there; the golden-section
/// search stops at |Δ ln α| < 1e-10 and J is quadratic around the minimum, so α is found to
/// far better than the 1e-6 relative asserted; kd and F0 follow from the exact 2×2 solve.
#[test]
fn fit_recovers_parameters() {
    let m = parsed();
    for (c, &(kd, f0, a)) in PARAMS.iter().enumerate() {
        let f = fit_ggx_lambert(m, c, [3, 6]).unwrap();
        assert!((f.alpha - a).abs() <= 1e-6 * a, "c{c}: {f:?}");
        assert!((f.kd - kd).abs() <= 1e-6, "c{c}: {f:?}");
        assert!((f.f0 - f0).abs() <= 1e-6, "c{c}: {f:?}");
        assert!(f.rel_rms <= 1e-6, "c{c}: {f:?}");
        assert!(f.nodes > 10_000 && !f.alpha_at_limit);
    }
}

/// |f_a − f_b| as a reflectance: its albedo bounds |E_a − E_b| (triangle inequality).
struct AbsDiff<'a>(&'a dyn Reflectance, &'a dyn Reflectance);

impl Reflectance for AbsDiff<'_> {
    fn eval(&self, wi: Dir, wo: Dir) -> f64 {
        (self.0.eval(wi, wo) - self.1.eval(wi, wo)).abs()
    }
    fn label(&self) -> String {
        "absdiff".into()
    }
    fn formula(&self) -> String {
        String::new()
    }
    fn source(&self) -> &'static str {
        ""
    }
    fn lobe_width(&self) -> f64 {
        0.05
    }
    fn tolerance_floor(&self) -> f64 {
        // it has the kinks of the interpolated data: as for measured data
        merl::MEASURED_TOLERANCE_FLOOR
    }
}

fn analytic(c: usize) -> brdfbake::model::classic::Microfacet {
    brdfbake::model::classic::Microfacet {
        brdf: model(c),
        label: format!("channel {c}"),
    }
}

/// The measured albedo of the synthetic file matches the analytic model's albedo within a
/// bound computed here, not assumed: |E_file − E_true| ≤ ∫|f_file − f_true| cos θo dωo
/// (itself integrated, plus all three quadrature error estimates). The bound must also be
/// small (< 2%): the interpolation resolves these lobes.
#[test]
fn measured_albedo_matches_analytic() {
    let m = parsed();
    let tol = 1e-5;
    for c in 0..3 {
        let ch = MerlChannel {
            merl: m.clone(),
            channel: c,
            label: String::new(),
        };
        let an = analytic(c);
        for th in [0.0f64, 40.0, 75.0] {
            let t = th.to_radians();
            let e_file = directional_albedo(&ch, t, 0.0, tol);
            let e_true = directional_albedo(&an, t, 0.0, 1e-9);
            let bound = directional_albedo(&AbsDiff(&ch, &an), t, 0.0, tol);
            let lim = bound.value + bound.error + e_file.error + e_true.error;
            assert!(
                (e_file.value - e_true.value).abs() <= lim,
                "c{c} th={th}: {} vs {} (bound {lim})",
                e_file.value,
                e_true.value
            );
            assert!(lim < 0.02, "c{c} th={th}: bound {lim}");
        }
    }
}

/// A file with unmeasured entries above the horizon: every 7th entry of G and all of the
/// last θd row of B are negative. The reader counts exactly those; the fit of G skips them
/// and still recovers the parameters; the albedo of G stays within the bound of the
/// interpolation difference to the complete file (computed as above).
#[test]
fn unmeasured_entries() {
    let mut b = bytes().clone();
    let neg = (-1.0f64).to_le_bytes();
    let mut holes = [0usize; 3];
    let m_full = parsed();
    for idx in (0..N).step_by(7) {
        if m_full.values[1][idx] >= 0.0 {
            let at = 12 + (N + idx) * 8;
            b[at..at + 8].copy_from_slice(&neg);
            holes[1] += 1;
        }
    }
    for i in 0..90 {
        for k in 0..180 {
            let idx = merl::index(i, 89, k);
            if m_full.values[2][idx] >= 0.0 {
                let at = 12 + (2 * N + idx) * 8;
                b[at..at + 8].copy_from_slice(&neg);
                holes[2] += 1;
            }
        }
    }
    let m = Arc::new(Merl::parse(&b).unwrap());
    let below = below_horizon_nodes();
    assert_eq!(m.unmeasured[0], below);
    assert_eq!(m.unmeasured[1], below + holes[1]);
    assert_eq!(m.unmeasured[2], below + holes[2]);
    assert_eq!(m.unmeasured_above_horizon, [0, holes[1], holes[2]]);
    assert!(holes[1] > 100_000 && holes[2] > 1000);
    let (kd, f0, a) = PARAMS[1];
    let f = fit_ggx_lambert(&m, 1, [3, 6]).unwrap();
    assert!(
        (f.alpha - a).abs() <= 1e-6 * a && (f.kd - kd).abs() <= 1e-6 && (f.f0 - f0).abs() <= 1e-6
    );
    for c in [1, 2] {
        let holed = MerlChannel {
            merl: m.clone(),
            channel: c,
            label: String::new(),
        };
        let full = MerlChannel {
            merl: m_full.clone(),
            channel: c,
            label: String::new(),
        };
        let t = 0.6f64;
        let e1 = directional_albedo(&holed, t, 0.0, 1e-5);
        let e2 = directional_albedo(&full, t, 0.0, 1e-5);
        let bound = directional_albedo(&AbsDiff(&holed, &full), t, 0.0, 1e-5);
        assert!(e1.value.is_finite());
        assert!((e1.value - e2.value).abs() <= bound.value + bound.error + e1.error + e2.error);
    }
}

/// Malformed files: each gives a specific error, never a panic.
#[test]
fn malformed_files_are_rejected() {
    let b = bytes();
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (Vec::new(), "shorter than the 12-byte header"),
        (b[..7].to_vec(), "shorter than the 12-byte header"),
        (b[..12].to_vec(), "truncated"),
        (b[..1000].to_vec(), "truncated"),
        (b[..FILE_BYTES - 1].to_vec(), "truncated"),
        (
            {
                let mut x = b.clone();
                x[0..4].copy_from_slice(&91i32.to_le_bytes());
                x
            },
            "header dimensions 91 90 180",
        ),
        (
            {
                let mut x = b.clone();
                x[8..12].copy_from_slice(&(-180i32).to_le_bytes());
                x
            },
            "header dimensions 90 90 -180",
        ),
        (
            {
                let mut x = b.clone();
                x.extend_from_slice(&[0; 8]);
                x
            },
            "8 trailing bytes",
        ),
        (
            {
                let mut x = b.clone();
                let at = 12 + (N + 5) * 8;
                x[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
                x
            },
            "channel G entry 5",
        ),
    ];
    for (data, needle) in cases {
        let e = Merl::parse(&data).unwrap_err();
        assert!(e.contains(needle), "{needle}: {e}");
    }
}

fn brdfbake(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_brdfbake"))
        .args(args)
        .output()
        .unwrap()
}

/// The CLI on files: `measured` reports the fit and albedo, `laws merl:FILE` reports three
/// channels (reciprocal by construction of the half/difference parameterization), bad
/// files exit 2 with the reason, a directory too.
#[test]
fn cli_on_files() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("synthetic.binary");
    std::fs::write(&good, bytes()).unwrap();
    let g = good.to_str().unwrap();
    let o = brdfbake(&["measured", g, "--albedo-size", "4", "--json"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let fit = &v["fit"]["channels"][1]["fit"];
    assert!((fit["alpha"].as_f64().unwrap() - 0.35).abs() < 1e-6);
    assert_eq!(v["albedo"]["rows"].as_array().unwrap().len(), 4);
    // deterministic: the same bytes on 1 and 2 threads
    let run_t = |t: &str| {
        Command::new(env!("CARGO_BIN_EXE_brdfbake"))
            .args(["measured", g, "--albedo-size", "4", "--json"])
            .env("RAYON_NUM_THREADS", t)
            .output()
            .unwrap()
            .stdout
    };
    assert_eq!(run_t("1"), run_t("2"));
    let o = brdfbake(&["laws", &format!("merl:{g}"), "--json"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let ms = v["models"].as_array().unwrap();
    assert_eq!(ms.len(), 3);
    for m in ms {
        assert_eq!(m["reciprocity"]["holds"], true, "{m}");
        assert_eq!(m["energy"]["holds"], true, "{m}");
    }
    let bad = dir.path().join("truncated.binary");
    std::fs::write(&bad, &bytes()[..123_456]).unwrap();
    let d = dir.path().to_str().unwrap();
    for (args, needle) in [
        (vec!["measured", bad.to_str().unwrap()], "truncated"),
        (
            vec!["laws", &format!("merl:{}", bad.display())],
            "truncated",
        ),
        (vec!["measured", d], "is a directory"),
        (vec!["measured", "/nonexistent/file.binary"], "no such file"),
    ] {
        let o = brdfbake(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// `measured --out`: different file names never write the same files (a name that needs
/// changing to be a file name gets a digest of itself), and `--fit` with `--no-fit` is an
/// error, not ignored.
#[test]
fn measured_out_names_never_collide() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let names = [
        "a b.binary",
        "a_b.binary",
        "a\u{202e}b.binary",
        "a\u{1b}b.binary",
    ];
    for n in names {
        std::fs::write(d.join(n), bytes()).unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_brdfbake"))
            .args([
                "measured",
                n,
                "--albedo-size",
                "4",
                "--no-fit",
                "--out",
                "out",
            ])
            .current_dir(d)
            .output()
            .unwrap();
        assert_eq!(
            o.status.code(),
            Some(0),
            "{n}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let exr: Vec<String> = std::fs::read_dir(d.join("out"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".exr"))
        .collect();
    assert_eq!(exr.len(), names.len(), "{exr:?}");
    assert!(exr.contains(&"a_b-albedo.exr".to_string()), "{exr:?}");
    let o = Command::new(env!("CARGO_BIN_EXE_brdfbake"))
        .args(["measured", "a_b.binary", "--no-fit", "--fit", "ggx"])
        .current_dir(d)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--no-fit") && err.contains("--fit"), "{err}");
}
