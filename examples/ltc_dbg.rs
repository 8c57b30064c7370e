use brdfbake::kernels::ltc_check::*;
use brdfbake::kernels::ltc_fit::*;
use brdfbake::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
fn main() {
    let a: Vec<String> = std::env::args().collect();
    if a[1] == "scan" {
        scan(a[2].parse().unwrap(), a[3].parse().unwrap());
        return;
    }
    if a[1] == "cmp" {
        let ls: Vec<usize> = a[4..].iter().map(|x| x.parse().unwrap()).collect();
        compare(a[2].parse().unwrap(), a[3].parse().unwrap(), &ls);
        return;
    }
    if a[1] == "timing" {
        timing();
        return;
    }
    if a[1] == "col" {
        col(a[2].parse().unwrap(), a[3].parse().unwrap());
        return;
    }
    if a[1] == "timing2" {
        timing2();
        return;
    }
    if a[1] == "line" {
        line(a[2].parse().unwrap(), a[3].parse().unwrap());
        return;
    }
    let mu: f64 = a[1].parse().unwrap();
    let r: f64 = a[2].parse().unwrap();
    let en: f64 = a[3].parse().unwrap();
    let lights: Vec<usize> = a[4..].iter().map(|x| x.parse().unwrap()).collect();
    let alpha = r * r;
    let brdf = Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
    };
    let opts = LtcFitOptions {
        energy_weight: en,
        probe_weight: std::env::var("PROBE")
            .map(|x| x.parse().unwrap())
            .unwrap_or(1.0),
        ..Default::default()
    };
    let shape = opts.shape();
    let t = fit_texel(&brdf, mu, None, &shape, &opts).unwrap();
    println!("fit {:?}", t);
    let v = view_vector(mu);
    let ls = test_lights();
    for li in lights {
        let l = &ls[li];
        let m = l.verts.iter().fold([0.0; 3], |a, v| {
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            [a[0] + v[0] / n, a[1] + v[1] / n, a[2] + v[2] / n]
        });
        let n = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        let c = [m[0] / n, m[1] / n, m[2] / n];
        let y = brdf.eval(v, c) * c[2] / t.norm;
        let x = t.ltc.eval(c);
        println!(
            "light {li}: center {:?} az {:.1}deg el {:.1}deg  y {y:e}  D {x:e}",
            c,
            c[1].atan2(c[0]).to_degrees(),
            c[2].asin().to_degrees()
        );
        let tr = lit_reference(&brdf, alpha, mu, l, 1e-7).unwrap();
        println!(
            "   truth {:e} ltc {:e}",
            tr.value,
            lit_ltc(&t.ltc, t.norm, l).unwrap()
        );
    }
    // profile along the horizon at elevation 5 deg for azimuths
    for el in [2.0f64, 10.0, 30.0] {
        let mut s = format!("el {el}: ");
        for az in (0..=12).map(|k| k as f64 * 15.0) {
            let (e, p) = (el.to_radians(), az.to_radians());
            let w = [e.cos() * p.cos(), e.cos() * p.sin(), e.sin()];
            let y = brdf.eval(v, w) * w[2] / t.norm;
            let x = t.ltc.eval(w);
            s += &format!("{az}:{:.1e}/{:.1e} ", y, x);
        }
        println!("{s}");
    }
}
#[allow(dead_code)]
pub fn line(r: f64, en: f64) {
    let alpha = (r * r).max(1e-5);
    let brdf = Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
    };
    let opts = LtcFitOptions {
        energy_weight: en,
        probe_weight: std::env::var("PROBE")
            .map(|x| x.parse().unwrap())
            .unwrap_or(1.0),
        ..Default::default()
    };
    let shape = opts.shape();
    let (mus, _) = brdfbake::table::ltc_layout::heitz_axes(64);
    let t = fit_line(&brdf, &mus, &shape, &opts).unwrap();
    for (i, x) in t.iter().enumerate() {
        let ax = x.ltc.axis();
        println!("{i} mu {:.4} mirror_el {:.2} a {:.3e} b {:.3e} c {:.3e} axis_el {:.2} obj {:.4} passes {}", mus[i], mus[i].asin().to_degrees(), x.ltc.a, x.ltc.b, x.ltc.c, ax[2].asin().to_degrees(), x.fit.objective, x.fit.passes);
    }
}
#[allow(dead_code)]
pub fn scan(mu: f64, r: f64) {
    let alpha = (r * r).max(1e-5);
    let brdf = Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
    };
    let opts = LtcFitOptions {
        probe_weight: std::env::var("PROBE")
            .map(|x| x.parse().unwrap())
            .unwrap_or(1.0),
        ..Default::default()
    };
    let shape = opts.shape();
    let t = fit_texel(&brdf, mu, None, &shape, &opts).unwrap();
    println!("{:?}", t);
    let v = view_vector(mu);
    // dense scan
    let mut worst = (0.0, 0.0, 0.0);
    let mut wsum = 0.0;
    let mut leak = 0.0;
    for i in 0..400 {
        for j in 0..800 {
            let el = (i as f64 + 0.5) / 400.0 * std::f64::consts::FRAC_PI_2;
            let az = (j as f64 + 0.5) / 800.0 * 2.0 * std::f64::consts::PI;
            let w = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
            let y = brdf.eval(v, w) * w[2] / t.norm;
            let x = t.ltc.eval(w);
            let da = el.cos()
                * (std::f64::consts::FRAC_PI_2 / 400.0)
                * (2.0 * std::f64::consts::PI / 800.0);
            if x > 3.0 * y {
                leak += x * da;
            }
            wsum += x * da;
            if x / (y + 1e-9) > worst.0 {
                worst = (x / (y + 1e-9), el.to_degrees(), az.to_degrees());
            }
        }
    }
    println!(
        "max ratio {:.3e} at el {:.2} az {:.1}; LTC mass where x>3y: {leak:.4} of {wsum:.4}",
        worst.0, worst.1, worst.2
    );
    let rule = brdfbake::kernels::ltc_rule::HemisphereRule::new(
        &shape,
        mu,
        brdfbake::hemisphere::LobeWarp::TanOverScale(alpha),
    );
    let mut wr = (0.0, 0.0, 0.0);
    for d in &rule.dirs {
        let y = brdf.eval(v, *d) * d[2] / t.norm;
        let x = t.ltc.eval(*d);
        if x / (y + 1e-9) > wr.0 {
            wr = (
                x / (y + 1e-9),
                d[2].asin().to_degrees(),
                d[1].atan2(d[0]).to_degrees(),
            );
        }
    }
    println!(
        "rule max ratio {:.3e} at el {:.2} az {:.1}",
        wr.0, wr.1, wr.2
    );
}
#[allow(dead_code)]
pub fn compare(mu: f64, r: f64, lights: &[usize]) {
    let alpha = (r * r).max(1e-5);
    let brdf = Brdf {
        specular: Some(Specular {
            ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(),
            masking: Masking::SmithHeightCorrelated,
            fresnel: Fresnel::None,
        }),
        diffuse_weight: 0.0,
    };
    let opts = LtcFitOptions::default();
    let t = fit_texel(&brdf, mu, None, &opts.shape(), &opts).unwrap();
    let js = brdfbake::table::ltc_layout::HeitzTable::from_js(include_str!(
        "../tests/data/ltc/heitz_ltc.js"
    ))
    .unwrap();
    let (h, hn, _) = js.ltc_at(mu, r).unwrap();
    println!("ours {:?} norm {}\nheitz {:?} norm {hn}", t.ltc, t.norm, h);
    let f = brdf_fcos(&brdf);
    let warp = brdfbake::hemisphere::LobeWarp::TanOverScale(alpha);
    println!(
        "objective: ours {:.5} heitz {:.5}",
        objective_at(&f, mu, warp, t.norm, &t.ltc, &opts.shape(), &opts).unwrap(),
        objective_at(&f, mu, warp, t.norm, &h, &opts.shape(), &opts).unwrap()
    );
    for (name, o) in [
        (
            "point",
            LtcFitOptions {
                energy_weight: 0.0,
                probe_weight: 0.0,
                ..opts
            },
        ),
        (
            "energy",
            LtcFitOptions {
                point_weight: 0.0,
                probe_weight: 0.0,
                ..opts
            },
        ),
        (
            "probe",
            LtcFitOptions {
                point_weight: 0.0,
                energy_weight: 0.0,
                ..opts
            },
        ),
    ] {
        println!(
            "  {name}: ours {:.5} heitz {:.5}",
            objective_at(&f, mu, warp, t.norm, &t.ltc, &o.shape(), &o).unwrap(),
            objective_at(&f, mu, warp, t.norm, &h, &o.shape(), &o).unwrap()
        );
    }
    let v = view_vector(mu);
    println!(
        "plane of incidence, mirror side (az 180) then view side (az 0): el: y / ours / heitz"
    );
    for az in [180.0f64, 0.0] {
        for el in [
            1.0f64, 3.0, 6.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0, 60.0, 70.0,
            80.0, 89.0,
        ] {
            let (e, p) = (el.to_radians(), az.to_radians());
            let w = [e.cos() * p.cos(), e.cos() * p.sin(), e.sin()];
            let y = brdf.eval(v, w) * w[2] / t.norm;
            println!(
                "  az {az} el {el}: {y:.3e} {:.3e} {:.3e}",
                t.ltc.eval(w),
                h.eval(w)
            );
        }
    }
    let ls = test_lights();
    for &li in lights {
        let l = &ls[li];
        let tr = lit_reference(&brdf, alpha, mu, l, 1e-7).unwrap().value;
        println!(
            "light {li}: verts {:?}\n   truth {tr:.4e} ours {:.4e} heitz {:.4e}",
            l.verts,
            lit_ltc(&t.ltc, t.norm, l).unwrap(),
            lit_ltc(&h, hn, l).unwrap()
        );
    }
}
#[allow(dead_code)]
pub fn timing() {
    let (mus, alphas) = brdfbake::table::ltc_layout::heitz_axes(64);
    let cpu = || {
        let mut ts = libc_timespec();
        ts
    };
    let _ = cpu;
    let t0 = std::time::Instant::now();
    let mut acc = 0.0;
    for &a in &alphas {
        let brdf = Brdf {
            specular: Some(Specular {
                ndf: Ndf::new(NdfKind::Ggx, a).unwrap(),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
            }),
            diffuse_weight: 0.0,
        };
        for &m in &mus {
            let r = norm_and_fresnel(&brdf, m, 1e-7);
            acc += r.0 + r.2;
        }
    }
    println!(
        "norm+fresnel 4096 texels: {:.3} s ({acc})",
        t0.elapsed().as_secs_f64()
    );
    let shape = LtcFitOptions::default().shape();
    let t0 = std::time::Instant::now();
    let mut n = 0;
    for &a in alphas.iter().step_by(8) {
        let brdf = Brdf {
            specular: Some(Specular {
                ndf: Ndf::new(NdfKind::Ggx, a).unwrap(),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
            }),
            diffuse_weight: 0.0,
        };
        for &m in mus.iter().step_by(8) {
            let r = brdfbake::kernels::ltc_rule::HemisphereRule::new(
                &shape,
                m,
                brdfbake::hemisphere::LobeWarp::TanOverScale(a),
            );
            let f = brdf_fcos(&brdf);
            for nd in &r.nodes {
                acc += f(nd);
            }
            n += 1;
        }
    }
    println!(
        "rule + brdf evals per texel: {:.1} us",
        t0.elapsed().as_secs_f64() / n as f64 * 1e6
    );
}
fn libc_timespec() -> u8 {
    0
}
#[allow(dead_code)]
pub fn timing2() {
    use std::time::Instant;
    let (mus, alphas) = brdfbake::table::ltc_layout::heitz_axes(64);
    let opts = LtcFitOptions::default();
    let shape = opts.shape();
    let mut n = 0;
    let mut acc = 0.0;
    let (mut t_rule, mut t_probe, mut t_fit) = (0.0, 0.0, 0.0);
    for &a in alphas.iter().step_by(4) {
        let brdf = Brdf {
            specular: Some(Specular {
                ndf: Ndf::new(NdfKind::Ggx, a).unwrap(),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
            }),
            diffuse_weight: 0.0,
        };
        let f = brdf_fcos(&brdf);
        for &m in mus.iter().step_by(4) {
            let t0 = Instant::now();
            let r = brdfbake::kernels::ltc_rule::HemisphereRule::new(
                &shape,
                m,
                brdfbake::hemisphere::LobeWarp::TanOverScale(a),
            );
            for nd in &r.nodes {
                acc += f(nd);
            }
            t_rule += t0.elapsed().as_secs_f64();
            let t0 = Instant::now();
            let p = brdfbake::kernels::ltc_probe::probes(
                [(1.0 - m * m).sqrt(), 0.0, m],
                &f,
                1.0,
                None,
                1e-9,
            );
            acc += p[0].y;
            t_probe += t0.elapsed().as_secs_f64();
            let t0 = Instant::now();
            let t = fit_texel(&brdf, m, None, &shape, &opts).unwrap();
            acc += t.norm;
            t_fit += t0.elapsed().as_secs_f64();
            n += 1;
        }
    }
    println!("per texel: rule+brdf {:.1} us, probes {:.1} us, whole fit_texel (no warm start) {:.1} us ({acc})", t_rule/n as f64*1e6, t_probe/n as f64*1e6, t_fit/n as f64*1e6);
}
#[allow(dead_code)]
pub fn col(n: usize, ai: usize) {
    let (mus, alphas) = brdfbake::table::ltc_layout::heitz_axes(n);
    let g = fit_grid(
        &|a| {
            Ok(Brdf {
                specular: Some(Specular {
                    ndf: Ndf::new(NdfKind::Ggx, a)?,
                    masking: Masking::SmithHeightCorrelated,
                    fresnel: Fresnel::None,
                }),
                diffuse_weight: 0.0,
            })
        },
        &mus,
        &alphas[ai..ai + 1],
        &LtcFitOptions::default(),
    )
    .unwrap();
    for (i, t) in g.texels.iter().enumerate() {
        println!(
            "{i} mu {:.5} {:?} cond {:.3e} obj {:.4} passes {}",
            mus[i],
            t.ltc,
            t.ltc.condition_number(),
            t.fit.objective,
            t.fit.passes
        );
    }
}
