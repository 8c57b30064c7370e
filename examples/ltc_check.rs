//! The LTC measurement: fits a 64² GGX table in Heitz's layout (timed on 1 and 2 threads,
//! compared bit for bit), then measures the relative error of the lit value of the test set
//! (`brdfbake::kernels::ltc_check`: 200 quad and triangle lights × 10 views × 10
//! roughnesses) against the quadrature ground truth for brdfbake's table, Heitz's published
//! `ltc.inc`, the same fit as three.js uploads it (`ltc.js` = three.js' `LTC_MAT_1/2`, as
//! f32 and as f16 textures) and, with `--fitltc`, the `ltc.js` of a local fitLTC rebuild.
//! Also: the ground truth's own error (a second centre and a 10× tighter tolerance on every
//! 7th case), the norm against brdfbake's albedo, and the conditioning of every texel.
//!
//! ```text
//! cargo run --release --example ltc_check -- [--fitltc DIR/results/ltc.js] [--quick]
//!                                           [--free-d] [--nphi N] [--nu N] [--no-timing]
//! ```
//! The ground truth is cached in `target/ltc-ground-truth-v1.txt` (delete it to recompute).

use brdfbake::kernels::ltc_check::{
    contains, error_stats, lit_ltc, lit_reference, lit_reference_about, mirror, test_lights,
    test_roughnesses, test_views, ErrorStats, PolygonLight,
};
use brdfbake::kernels::ltc_fit::{fit_grid, LtcFitOptions, LtcGrid};
use brdfbake::table::albedo::directional_albedo;
use brdfbake::table::ltc_heldout::ggx;
use brdfbake::table::ltc_layout::{heitz_axes, HeitzTable, TexelStorage, HEITZ_SIZE};
use rayon::prelude::*;
use std::time::Instant;

const TRUTH_TOL: f64 = 1e-7;

/// CPU time of the whole process (every thread), seconds.
fn process_cpu_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    assert_eq!(rc, 0, "clock_gettime");
    t.tv_sec as f64 + 1e-9 * t.tv_nsec as f64
}
const CACHE: &str = "target/ltc-ground-truth-v1.txt";
const CACHE_TEXELS: &str = "target/ltc-ground-truth-texels-v1.txt";

struct Case {
    light: usize,
    mu: f64,
    r: f64,
    truth: f64,
    truth_err: f64,
}

fn ground_truth(lights: &[PolygonLight], quick: bool, at_texels: bool) -> Vec<Case> {
    let mut views = test_views();
    let mut rough = test_roughnesses();
    if at_texels {
        // the nearest texel rows and columns of the 64² table: no interpolation
        let n = HEITZ_SIZE;
        views = views
            .iter()
            .map(|&mu| {
                let t = ((1.0 - mu).sqrt() * (n - 1) as f64).round() as usize;
                brdfbake::table::ltc_layout::heitz_row_mu(t, n)
            })
            .collect();
        rough = rough
            .iter()
            .map(|&r| (r * (n - 1) as f64).round() / (n - 1) as f64)
            .collect();
    }
    let mut keys = Vec::new();
    for (li, _) in lights.iter().enumerate() {
        if quick && li % 4 != 0 {
            continue;
        }
        for &mu in &views {
            for &r in &rough {
                keys.push((li, mu, r));
            }
        }
    }
    let tag = format!("v1 tol={TRUTH_TOL:e} n={} texels={at_texels}", keys.len());
    let cache = if at_texels { CACHE_TEXELS } else { CACHE };
    if let Ok(text) = std::fs::read_to_string(cache) {
        let mut lines = text.lines();
        if lines.next() == Some(tag.as_str()) {
            let vals: Vec<(f64, f64)> = lines
                .filter_map(|l| {
                    let mut it = l.split_whitespace().map(|x| x.parse::<f64>());
                    Some((it.next()?.ok()?, it.next()?.ok()?))
                })
                .collect();
            if vals.len() == keys.len() {
                eprintln!("ground truth: {} cases from {cache}", vals.len());
                return keys
                    .iter()
                    .zip(vals)
                    .map(|(&(light, mu, r), (truth, truth_err))| Case {
                        light,
                        mu,
                        r,
                        truth,
                        truth_err,
                    })
                    .collect();
            }
        }
    }
    let t0 = Instant::now();
    let cases: Vec<Case> = keys
        .par_iter()
        .map(|&(light, mu, r)| {
            let alpha = r * r;
            let brdf = ggx(alpha).expect("alpha in range");
            let e =
                lit_reference(&brdf, alpha, mu, &lights[light], TRUTH_TOL).expect("valid light");
            Case {
                light,
                mu,
                r,
                truth: e.value,
                truth_err: e.error,
            }
        })
        .collect();
    eprintln!(
        "ground truth: {} cases in {:.1} s",
        cases.len(),
        t0.elapsed().as_secs_f64()
    );
    let mut s = tag + "\n";
    for c in &cases {
        s += &format!("{:e} {:e}\n", c.truth, c.truth_err);
    }
    let _ = std::fs::write(cache, s);
    cases
}

/// The ground truth's own error: a second centre (the light's vertex mean) and scale, 10×
/// tighter, on every 7th case.
fn truth_check(lights: &[PolygonLight], cases: &[Case]) {
    let sub: Vec<&Case> = cases.iter().step_by(7).collect();
    let worst = sub
        .par_iter()
        .map(|c| {
            let alpha = c.r * c.r;
            let brdf = ggx(alpha).unwrap();
            let l = &lights[c.light];
            let m = l.verts.iter().fold([0.0; 3], |a, v| {
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                [a[0] + v[0] / n, a[1] + v[1] / n, a[2] + v[2] / n]
            });
            let e = lit_reference_about(&brdf, c.mu, l, m, 0.5 * alpha + 1e-3, 0.1 * TRUTH_TOL)
                .unwrap();
            ((e.value - c.truth).abs() / c.truth, c.truth_err / c.truth)
        })
        .reduce(|| (0.0, 0.0), |a, b| (a.0.max(b.0), a.1.max(b.1)));
    println!(
        "ground truth: {} cases checked against a second centre at 1e-8: largest relative difference {:.2e} (largest own estimate {:.2e})",
        sub.len(),
        worst.0,
        worst.1
    );
}

fn row(name: &str, s: &ErrorStats) {
    println!(
        "{name:<34} {:>7} {:>9.4} {:>9.4} {:>9.4} {:>9.3} {:>8.2}%",
        s.count,
        s.median,
        s.p90,
        s.p99,
        s.max,
        100.0 * s.zeros
    );
}

fn measure(table: &HeitzTable, lights: &[PolygonLight], cases: &[Case]) -> [ErrorStats; 4] {
    let res: Vec<(f64, f64, bool, bool)> = cases
        .par_iter()
        .map(|c| {
            let (ltc, norm, _) = table.ltc_at(c.mu, c.r).expect("valid table");
            let l = &lights[c.light];
            let v = lit_ltc(&ltc, norm, l).expect("valid light");
            let rel = (v - c.truth).abs() / c.truth;
            (rel, v, contains(&l.verts, mirror(c.mu)), l.crosses_horizon)
        })
        .collect();
    let all: Vec<(f64, f64)> = res.iter().map(|x| (x.0, x.1)).collect();
    let inside: Vec<(f64, f64)> = res.iter().filter(|x| x.2).map(|x| (x.0, x.1)).collect();
    let outside: Vec<(f64, f64)> = res.iter().filter(|x| !x.2).map(|x| (x.0, x.1)).collect();
    let crossing: Vec<(f64, f64)> = res.iter().filter(|x| x.3).map(|x| (x.0, x.1)).collect();
    [
        error_stats(&all),
        error_stats(&inside),
        error_stats(&outside),
        error_stats(&crossing),
    ]
}

fn fit(opts: &LtcFitOptions) -> LtcGrid {
    let (mus, alphas) = heitz_axes(HEITZ_SIZE);
    fit_grid(&ggx, &mus, &alphas, opts).expect("fit")
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let flag = |f: &str| args.iter().any(|a| a == f);
    let value = |f: &str| {
        args.iter()
            .position(|a| a == f)
            .and_then(|i| args.get(i + 1).cloned())
    };
    let mut opts = LtcFitOptions::default();
    if let Some(v) = value("--energy") {
        opts.energy_weight = v.parse().expect("--energy L");
    }
    if let Some(v) = value("--floor") {
        opts.floor = v.parse().expect("--floor F");
    }
    if flag("--d0") {
        opts.free_d = false;
    }
    if let Some(v) = value("--point") {
        opts.point_weight = v.parse().expect("--point W");
    }
    if let Some(v) = value("--probe") {
        opts.probe_weight = v.parse().expect("--probe W");
    }
    if let Some(v) = value("--rule") {
        let r: Vec<usize> = v
            .split(',')
            .map(|x| x.parse().expect("--rule A,B,C,D"))
            .collect();
        opts.rule = [r[0], r[1], r[2], r[3]];
    }
    println!("fit options: {opts:?}");

    // 1. the fit, timed on one and two threads
    let grid = if flag("--no-timing") {
        let t0 = Instant::now();
        let g = fit(&opts);
        println!(
            "64^2 GGX fit: {:.3} s wall (default pool)",
            t0.elapsed().as_secs_f64()
        );
        g
    } else {
        let mut walls = Vec::new();
        let mut grids = Vec::new();
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
            let (t0, c0) = (Instant::now(), process_cpu_seconds());
            let g = pool.install(|| fit(&opts));
            let (w, c) = (t0.elapsed().as_secs_f64(), process_cpu_seconds() - c0);
            println!(
                "64^2 GGX fit on {threads} thread(s): {w:.3} s wall, {c:.3} s CPU (load average before: {})",
                load.split_whitespace().take(3).collect::<Vec<_>>().join(" ")
            );
            walls.push(w);
            grids.push(g);
        }
        println!("speed-up 1 -> 2 threads: {:.2}x", walls[0] / walls[1]);
        let same = grids[0].texels == grids[1].texels;
        println!("1-thread and 2-thread tables bit-identical: {same}");
        grids.swap_remove(1)
    };
    let passes: usize = grid.texels.iter().map(|t| t.fit.passes).sum();
    println!(
        "optimizer passes: {} total, {:.1} per texel",
        passes,
        passes as f64 / grid.texels.len() as f64
    );

    if flag("--fit-only") {
        return;
    }

    // 2. conditioning and norm
    let mut worst_ca: f64 = 0.0;
    let mut worst_cam: f64 = 0.0;
    let mut worst_c: f64 = 0.0;
    let mut all_finite = true;
    for (i, t) in grid.texels.iter().enumerate() {
        let alpha = grid.alphas[i % grid.alphas.len()];
        let mu = grid.mus[i / grid.alphas.len()];
        let c = t.ltc.condition_number();
        all_finite &= [t.ltc.a, t.ltc.b, t.ltc.c, t.ltc.d, t.norm, t.fresnel]
            .iter()
            .all(|x| x.is_finite());
        worst_c = worst_c.max(c);
        if mu >= 0.17 {
            worst_ca = worst_ca.max(c * alpha);
        }
        worst_cam = worst_cam.max(c * alpha * mu);
    }
    println!(
        "conditioning: every entry finite: {all_finite}; largest cond(M^-1) {worst_c:.3e}; largest cond*alpha (cos theta >= 0.17) {worst_ca:.3}; largest cond*alpha*mu {worst_cam:.3}"
    );
    // every bilinear lookup inside every cell must give an invertible M⁻¹: 9 × 9 points a cell
    let table = HeitzTable::from_grid(&grid).expect("table");
    let n = HEITZ_SIZE;
    let mut bad = 0usize;
    let mut worst_det = f64::INFINITY;
    for t in 0..n - 1 {
        for a in 0..n - 1 {
            for i in 0..=8 {
                for j in 0..=8 {
                    let x = (t as f64 + i as f64 / 8.0) / (n - 1) as f64;
                    let r = (a as f64 + j as f64 / 8.0) / (n - 1) as f64;
                    let (t1, _) = table.lookup(1.0 - x * x, r).expect("lookup");
                    let det = t1[0] * t1[3] - t1[1] * t1[2];
                    worst_det = worst_det.min(det / (t1[0].abs() * t1[3].abs()));
                    if brdfbake::model::ltc::Ltc::from_heitz_texel(t1).is_err() {
                        bad += 1;
                    }
                }
            }
        }
    }
    println!(
        "interpolated lookups (9 x 9 a cell): {bad} not invertible; smallest det/(|m00 m22|) {worst_det:.3e}"
    );
    let mut worst_norm: f64 = 0.0;
    for (i, t) in grid.texels.iter().enumerate() {
        let (mu, alpha) = (
            grid.mus[i / grid.alphas.len()],
            grid.alphas[i % grid.alphas.len()],
        );
        let (e, _, _) = directional_albedo(&ggx(alpha).unwrap(), mu, opts.tolerance);
        worst_norm = worst_norm.max((e[0] - t.norm).abs());
    }
    println!("norm vs brdfbake's directional albedo: largest |difference| {worst_norm:e}");
    let heitz_js = include_str!("../tests/data/ltc/heitz_ltc.js");
    let heitz_inc = include_str!("../tests/data/ltc/heitz_ltc.inc");
    let js = HeitzTable::from_js(heitz_js).expect("ltc.js");
    let mut worst_heitz_norm: f64 = 0.0;
    for (i, t) in grid.texels.iter().enumerate() {
        worst_heitz_norm = worst_heitz_norm.max((js.ltc_2[i][0] - t.norm).abs() / t.norm);
    }
    println!(
        "Heitz's published norm vs brdfbake's: largest relative difference {worst_heitz_norm:.3e}"
    );

    // 3. the lit error
    let lights = test_lights();
    let cases = ground_truth(&lights, flag("--quick"), flag("--at-texels"));
    if !flag("--quick") {
        truth_check(&lights, &cases);
    }
    let ours = HeitzTable::from_grid(&grid).expect("table");
    let mut tables: Vec<(String, HeitzTable)> = vec![
        ("brdfbake (f64)".into(), ours.clone()),
        ("brdfbake (f32)".into(), ours.stored(TexelStorage::F32)),
        ("brdfbake (f16)".into(), ours.stored(TexelStorage::F16)),
        (
            "Heitz ltc.inc".into(),
            HeitzTable::from_inc(heitz_inc).expect("ltc.inc"),
        ),
        (
            "Heitz ltc.js = three.js (f32)".into(),
            js.stored(TexelStorage::F32),
        ),
        (
            "three.js HalfFloat (f16)".into(),
            js.stored(TexelStorage::F16),
        ),
    ];
    if let Some(p) = value("--fitltc") {
        let text = std::fs::read_to_string(&p).expect("--fitltc file");
        tables.push((
            "fitLTC rebuild (f32)".into(),
            HeitzTable::from_js(&text)
                .expect("fitLTC ltc.js")
                .stored(TexelStorage::F32),
        ));
    }
    let header = format!(
        "{:<34} {:>7} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "table", "cases", "median", "p90", "p99", "max", "zeros"
    );
    let results: Vec<(String, [ErrorStats; 4])> = tables
        .iter()
        .map(|(n, t)| (n.clone(), measure(t, &lights, &cases)))
        .collect();
    if let Some(p) = value("--dump") {
        // one line per (table, case): for offline analysis
        let mut s = String::from("table,light,mu,r,truth,value,inside,crossing,cz\n");
        for (ti, (_, t)) in tables.iter().enumerate() {
            for c in &cases {
                let (ltc, norm, _) = t.ltc_at(c.mu, c.r).unwrap();
                let l = &lights[c.light];
                let v = lit_ltc(&ltc, norm, l).unwrap();
                let m = l
                    .verts
                    .iter()
                    .fold([0.0; 3], |a, v| [a[0] + v[0], a[1] + v[1], a[2] + v[2]]);
                let cz = m[2] / (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
                s += &format!(
                    "{ti},{},{},{},{:e},{:e},{},{},{cz}\n",
                    c.light,
                    c.mu,
                    c.r,
                    c.truth,
                    v,
                    contains(&l.verts, mirror(c.mu)) as u8,
                    l.crosses_horizon as u8
                );
            }
        }
        std::fs::write(&p, s).expect("--dump file");
    }
    for (k, title) in [
        "all cases",
        "mirror direction inside the light",
        "mirror direction outside the light",
        "lights crossing the horizon",
    ]
    .iter()
    .enumerate()
    {
        println!("\nrelative error of the lit value, {title}:\n{header}");
        for (n, s) in &results {
            row(n, &s[k]);
        }
    }
}
