//! The LTC core (issue 25): the distribution, its polygon integral, the fit's determinism,
//! its norm channel, its conditioning, and the layout's round trip.

use brdfbake::kernels::ltc_fit::{fit_grid, LtcFitOptions, LtcGrid};
use brdfbake::kernels::ltc_polygon::{cap_clamped_cosine, ltc_polygon_integral};
use brdfbake::kernels::ltc_reference::{clip_to_halfspace, polygon_integral};
use brdfbake::lut::{Axis, Convention, Quantity};
use brdfbake::model::ltc::Ltc;
use brdfbake::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, RoughnessQuantity, Specular};
use brdfbake::table::ltc_layout::{heitz_axes, HeitzTable, TexelStorage};
use brdfbake::table::{bake, ModelSpec, Storage, TableKind, TableSpec};
use std::f64::consts::PI;

fn ggx(alpha: f64) -> Result<Brdf, String> {
    Ok(Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha)?,
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
        diffuse: brdfbake::model::DiffuseLobe::Lambert,
    })
}

/// LTCs of every kind the fit makes: the identity, narrow and wide lobes, tilted axes and
/// tilted supports (d < 0), and one near the α = 10⁻⁵ end.
fn ltcs() -> Vec<Ltc> {
    vec![
        Ltc::IDENTITY,
        Ltc::new(3.0, 0.0, 3.0, 0.0).unwrap(),
        Ltc::new(5.2, 6.0, 9.0, -0.2).unwrap(),
        Ltc::new(7.7, 8.8, 17.8, -1.1).unwrap(),
        Ltc::new(0.4, 12.0, 25.0, -3.0).unwrap(),
        Ltc::new(2.0e4, 1.0e4, 5.0e4, 0.0).unwrap(),
    ]
}

/// The eight octants of the sphere, counterclockwise about the outward direction.
fn octants() -> Vec<Vec<[f64; 3]>> {
    let mut out = Vec::new();
    for sx in [1.0, -1.0] {
        for sy in [1.0, -1.0] {
            for sz in [1.0, -1.0] {
                let mut t = vec![[sx, 0.0, 0.0], [0.0, sy, 0.0], [0.0, 0.0, sz]];
                // orientation: (p1 − p0) × (p2 − p0) · p0 > 0
                let (p0, p1, p2) = (t[0], t[1], t[2]);
                let e1 = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
                let e2 = [p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]];
                let n = [
                    e1[1] * e2[2] - e1[2] * e2[1],
                    e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0],
                ];
                if n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2] < 0.0 {
                    t.reverse();
                }
                out.push(t);
            }
        }
    }
    out
}

/// The lobe's width for the reference quadrature's radial warp: the smallest half-width
/// of the sheared cosine about its axis, 1/(largest singular value of M⁻¹).
fn width(l: &Ltc) -> f64 {
    (1.0 / l.singular_values()[0]).min(1.0)
}

/// ∫ D over the sphere = 1 by direct quadrature of D (no change of variables): the octants,
/// each clipped to D's support `(M⁻¹ω)_z > 0` (where D has a kink), by the adaptive polar
/// rule about the lobe's axis to relative 1e-10. The rule's error estimates bound its error
/// in practice (G7/K15 on a smooth integrand); the sum of eight such parts is within 1e-8
/// of its value, which is what is asserted.
#[test]
fn distribution_integrates_to_one() {
    for l in ltcs() {
        let support = [l.d, 0.0, 1.0];
        let mut total = 0.0;
        for o in octants() {
            let p = clip_to_halfspace(&o, support);
            let r = polygon_integral(&|w| l.eval(w), &p, l.axis(), width(&l), 1e-10).unwrap();
            total += r.value;
        }
        assert!((total - 1.0).abs() < 1e-8, "{l:?}: {total}");
        // and the closed-form upper-hemisphere mass against the upper octants
        let mut upper = 0.0;
        for o in octants().iter().filter(|o| o.iter().any(|v| v[2] > 0.0)) {
            let p = clip_to_halfspace(o, support);
            upper += polygon_integral(&|w| l.eval(w), &p, l.axis(), width(&l), 1e-10)
                .unwrap()
                .value;
        }
        assert!(
            (upper - l.upper_hemisphere_mass()).abs() < 1e-8,
            "{l:?}: {upper} vs {}",
            l.upper_hemisphere_mass()
        );
    }
}

/// The closed-form polygon integral (Lambert's edge formula after M⁻¹ and the clip) against
/// direct quadrature of D over the polygon, for the test set's lights (quads and triangles,
/// some crossing the horizon) and every LTC above. The closed form is exact up to rounding
/// (atan2 and cross products: ~1e-15 relative an edge); the quadrature runs at relative
/// 1e-10; asserted: 1e-8 relative (or 1e-14 absolute for values that are ~0).
#[test]
fn polygon_integral_matches_quadrature() {
    let lights = brdfbake::kernels::ltc_check::test_lights();
    for l in ltcs() {
        let support = [l.d, 0.0, 1.0];
        for light in lights.iter().step_by(9) {
            let closed = ltc_polygon_integral(&l, &light.verts).unwrap();
            let p = clip_to_halfspace(&light.verts, support);
            let q = polygon_integral(&|w| l.eval(w), &p, l.axis(), width(&l), 1e-10).unwrap();
            assert!(
                (closed - q.value).abs() <= 1e-8 * q.value.abs() + 1e-14,
                "{l:?} {:?}: closed {closed} quadrature {q:?}",
                light.verts
            );
        }
    }
}

/// The horizon-clipped cap (Snyder's formula) against direct quadrature of the clamped
/// cosine over caps above, across and below the horizon: the cap as a fine inscribed
/// polygon (an 8192-gon, whose area falls short of the cap's by ~(2π/8192)²/6 relative:
/// 1e-7, and up to 3e-7 of a small clipped remainder) by the closed-form edge sum, so
/// asserted at 1e-6 relative.
#[test]
fn clipped_cap_matches_a_fine_polygon() {
    for (omega, sigma) in [(0.3, 0.2), (1.3, 0.4), (1.6, 0.3), (1.9, 0.5), (0.9, 1.2)] {
        let c = [f64::sin(omega), 0.0, f64::cos(omega)];
        let e1 = [f64::cos(omega), 0.0, -f64::sin(omega)];
        let e2 = [0.0, 1.0, 0.0];
        let n = 8192;
        let poly: Vec<[f64; 3]> = (0..n)
            .map(|k| {
                let t = 2.0 * PI * k as f64 / n as f64;
                let (s, co) = t.sin_cos();
                let (ss, cs) = f64::sin_cos(sigma);
                [
                    cs * c[0] + ss * (co * e1[0] + s * e2[0]),
                    cs * c[1] + ss * (co * e1[1] + s * e2[1]),
                    cs * c[2] + ss * (co * e1[2] + s * e2[2]),
                ]
            })
            .collect();
        let poly_value = brdfbake::kernels::ltc_polygon::clamped_cosine_integral(&poly).unwrap();
        let exact = cap_clamped_cosine(omega, sigma).unwrap();
        assert!(
            (poly_value - exact).abs() < 1e-6 * exact + 1e-12,
            "ω {omega} σ {sigma}: polygon {poly_value} formula {exact}"
        );
    }
}

fn small_grid_opts() -> LtcFitOptions {
    LtcFitOptions::default()
}

/// Bit-identical fits on one and two threads, and whatever the order of the views given.
#[test]
fn fit_is_deterministic_across_threads_and_order() {
    let mus = vec![1.0, 0.8, 0.5, 0.3, 0.1, 0.02];
    let alphas = vec![1e-5, 0.01, 0.1, 0.3, 1.0];
    let run = |threads: usize, mus: &[f64]| -> LtcGrid {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| fit_grid(&ggx, mus, &alphas, &small_grid_opts()).unwrap())
    };
    let one = run(1, &mus);
    let two = run(2, &mus);
    assert_eq!(one.texels, two.texels);
    let mut rev = mus.clone();
    rev.reverse();
    let r = run(2, &rev);
    for (i, _) in mus.iter().enumerate() {
        for j in 0..alphas.len() {
            assert_eq!(one.get(i, j), r.get(mus.len() - 1 - i, j));
        }
    }
}

/// The norm channel is brdfbake's own albedo: an `albedo` table baked at the same views and
/// roughnesses holds the same numbers (the same integrator at the same tolerance: equal to
/// well within the 1e-6 that is asserted).
#[test]
fn norm_is_brdfbakes_albedo() {
    let axes = vec![
        Axis {
            name: "cos_theta_v".into(),
            quantity: Quantity::Cosine,
            size: 6,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        },
        Axis {
            name: "roughness".into(),
            quantity: Quantity::Roughness(RoughnessQuantity::Perceptual),
            size: 5,
            range: [0.0, 1.0],
            convention: Convention::Centers,
            warp: Default::default(),
            clamp: None,
        },
    ];
    let spec = TableSpec {
        name: "e".into(),
        kind: TableKind::Albedo,
        model: ModelSpec {
            ndf: Some(NdfKind::Ggx),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
            diffuse_weight: 0.0,
            diffuse_model: brdfbake::model::DiffuseModel::Lambert,
            classic: None,
        },
        axes: axes.clone(),
        dfg_layout: None,
        cloth: false,
        cloth_alpha_min: None,
        ltc_channels: None,
        storage: Storage::F32,
        tolerance: 1e-7,
    };
    let lut = bake(&spec).unwrap();
    let mus = axes[0].coords();
    let alphas: Vec<f64> = (0..5).map(|j| axes[1].alpha(j).unwrap()).collect();
    let grid = fit_grid(&ggx, &mus, &alphas, &small_grid_opts()).unwrap();
    for (i, &mu) in mus.iter().enumerate() {
        for (j, &alpha) in alphas.iter().enumerate() {
            let e = lut.lookup(&[mu, alpha.sqrt()])[0];
            let n = grid.get(i, j).unwrap().norm;
            assert!(
                (e - n).abs() < 1e-6,
                "mu {mu} alpha {alpha}: albedo {e} norm {n}"
            );
        }
    }
}

/// A 16² table in Heitz's layout (α = 10⁻⁵ to 1, cos θ = 1 down to the θ = 1.57 row):
/// every M⁻¹ finite and conditioned as its lobe requires — a lobe of width α about the
/// mirror direction needs `cond(M⁻¹) ~ 1/α`, and at grazing views, where the reflected
/// lobe's width across the plane of incidence shrinks to `2μα` and its axis leans to the
/// horizon, up to `~1/(μα)`: asserted `cond·α ≤ 20` for cos θ ≥ 0.17 (θ ≤ 80°; the 64²
/// table reaches 11 there, `examples/ltc_check.rs`) and `cond·α·μ ≤ 10` at every row (it
/// reaches 3.2) —, every bilinear lookup inside every cell invertible (9 × 9
/// points a cell), and every texel read back through the documented lookup at its own
/// coordinates, in f64 (to 1e-9: the lookup's √(1 − μ) rounds) and as f32 and f16 textures
/// (to their rounding: 1e-6 and 2e-3 relative an entry, amplified by at most the
/// conditioning of the 2×2 inverse).
#[test]
fn table_is_well_conditioned_and_round_trips() {
    let n = 16;
    let (mus, alphas) = heitz_axes(n);
    let grid = fit_grid(&ggx, &mus, &alphas, &small_grid_opts()).unwrap();
    for (k, t) in grid.texels.iter().enumerate() {
        let alpha = alphas[k % n];
        let mu = mus[k / n];
        let l = t.ltc;
        assert!([l.a, l.b, l.c, l.d, t.norm, t.fresnel]
            .iter()
            .all(|x| x.is_finite()));
        let c = l.condition_number();
        if mu >= 0.17 {
            assert!(
                c * alpha <= 10.0,
                "texel {k}: cond {c} alpha {alpha} mu {mu}"
            );
        }
        assert!(
            c * alpha * mu <= 10.0,
            "texel {k}: cond {c} alpha {alpha} mu {mu}"
        );
        assert!(t.norm > 0.0 && t.fresnel >= 0.0 && t.fresnel <= t.norm);
    }
    let table = HeitzTable::from_grid(&grid).unwrap();
    for t in 0..n - 1 {
        for a in 0..n - 1 {
            for i in 0..=8 {
                for j in 0..=8 {
                    let x = (t as f64 + i as f64 / 8.0) / (n - 1) as f64;
                    let r = (a as f64 + j as f64 / 8.0) / (n - 1) as f64;
                    let (t1, _) = table.lookup(1.0 - x * x, r).unwrap();
                    assert!(Ltc::from_heitz_texel(t1).is_ok(), "cell {t} {a}: {t1:?}");
                }
            }
        }
    }
    for (storage, tol) in [
        (TexelStorage::F64, 1e-9),
        (TexelStorage::F32, 1e-6),
        (TexelStorage::F16, 2e-3),
    ] {
        let st = table.stored(storage);
        for t in 0..n {
            for a in 0..n {
                let x = t as f64 / (n - 1) as f64;
                let r = a as f64 / (n - 1) as f64;
                let (got, norm, fresnel) = st.ltc_at(1.0 - x * x, r).unwrap();
                let want = grid.get(t, a).unwrap();
                let h = want.ltc.heitz_texel();
                let g = got.heitz_texel();
                for k in 0..4 {
                    let scale = h.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    assert!(
                        (g[k] - h[k]).abs() <= tol * scale,
                        "{storage:?} texel ({t}, {a}) entry {k}: {} vs {}",
                        g[k],
                        h[k]
                    );
                }
                assert!((norm - want.norm).abs() <= tol * want.norm.max(1e-3));
                assert!((fresnel - want.fresnel).abs() <= tol * want.norm.max(1e-3));
            }
        }
    }
    // and through the text forms the published tables use
    let js = to_js(&table);
    assert_eq!(HeitzTable::from_js(&js).unwrap(), table);
}

fn to_js(t: &HeitzTable) -> String {
    let arr = |v: &[[f64; 4]]| {
        v.iter()
            .flat_map(|x| x.iter().map(|y| format!("{y:e}")))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "const LTC_MAT_1 = [ {} ];\nconst LTC_MAT_2 = [ {} ];\n",
        arr(&t.ltc_1),
        arr(&t.ltc_2)
    )
}

/// The published tables read as documented: 64², and the norm channel of `ltc.js` equals
/// `ltc.inc`'s magnitudes; `ltc.inc`'s normalized `M⁻¹` equals `ltc.js`' `ltc_1` to the
/// files' printed precision (`%.6f` of entries up to ~1e5 in `ltc.inc`, 6 significant
/// digits in `ltc.js`).
#[test]
fn published_tables_read_consistently() {
    let js = HeitzTable::from_js(include_str!("data/ltc/heitz_ltc.js")).unwrap();
    let inc = HeitzTable::from_inc(include_str!("data/ltc/heitz_ltc.inc")).unwrap();
    assert_eq!((js.n, inc.n), (64, 64));
    for i in 0..64 * 64 {
        assert_eq!(js.ltc_2[i][0], inc.ltc_2[i][0], "texel {i}");
        for k in 0..4 {
            let (a, b) = (js.ltc_1[i][k], inc.ltc_1[i][k]);
            assert!(
                (a - b).abs() <= 2e-5 * a.abs().max(1.0),
                "texel {i} entry {k}: {a} {b}"
            );
        }
    }
}
