//! Compares the classic-albedo fast path (`src/kernels/classic_lobes.rs`) with the
//! energy-law integrator at a 100× tighter tolerance over a grid of views and parameters,
//! and prints per model: texels, fallbacks, evaluations per texel (mean / max), the largest
//! |fast − laws| and the largest ratio of that difference to the two estimates.
//! `cargo run --release --example classic_fast_check -- [cosines] [parameters] [tol]`
//! (default 16 8 1e-7: the grid of presets/classic-albedo.json, texel centres).

use brdfbake::table::classic::{fast_albedo, view_albedo, ClassicModel};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let nmu: usize = a.get(1).map_or(16, |s| s.parse().unwrap());
    let np: usize = a.get(2).map_or(8, |s| s.parse().unwrap());
    let tol: f64 = a.get(3).map_or(1e-7, |s| s.parse().unwrap());
    let models = [
        (ClassicModel::BlinnPhong { ks: 1.0 }, [0.0, 256.0]),
        (
            ClassicModel::ModifiedPhong { kd: 0.0, ks: 1.0 },
            [0.0, 256.0],
        ),
        (ClassicModel::Phong { ks: 1.0 }, [0.0, 256.0]),
        (
            ClassicModel::WardGmd {
                rho_d: 0.0,
                rho_s: 1.0,
            },
            [0.0, 0.8],
        ),
    ];
    println!("| model | texels | fallbacks | evals/texel mean | max | laws evals/texel | max |fast - laws| | max diff/(est + ref est) | at (mu, p) |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---|");
    for (c, [lo, hi]) in models {
        let (mut n, mut fb, mut ev, mut evmax, mut lev) = (0u64, 0u64, 0u64, 0u64, 0u64);
        let (mut worst, mut ratio, mut at) = (0.0f64, 0.0f64, (0.0, 0.0));
        for i in 0..nmu {
            let mu = (i as f64 + 0.5) / nmu as f64;
            for j in 0..np {
                let p = lo + (hi - lo) * (j as f64 + 0.5) / np as f64;
                n += 1;
                let r = view_albedo(c.reflectance(p, 1.0), mu, 0.0, tol / 100.0);
                let base = view_albedo(c.reflectance(p, 1.0), mu, 0.0, tol);
                lev += base.evals;
                match fast_albedo(&c, mu, p, tol).unwrap() {
                    Ok(f) => {
                        ev += f.evals;
                        evmax = evmax.max(f.evals);
                        let d = (f.value - r.value).abs();
                        if d > worst {
                            worst = d;
                            at = (mu, p);
                        }
                        ratio = ratio.max(d / (f.error + r.error));
                    }
                    Err(spent) => {
                        fb += 1;
                        ev += spent + base.evals;
                    }
                }
            }
        }
        println!(
            "| {} | {n} | {fb} | {:.0} | {evmax} | {:.0} | {worst:.1e} | {ratio:.2} | {at:?} |",
            c.name(),
            ev as f64 / n as f64,
            lev as f64 / n as f64
        );
    }
}
