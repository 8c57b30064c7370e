use brdfbake::model::*;
use brdfbake::table::dfg::*;
fn main() {
    for &mu in &[0.5 / 128.0, 1.5 / 128.0, 0.1, 0.9] {
        for &r in &[0.5 / 128.0f64, 1.5 / 128.0, 10.5 / 128., 0.5, 0.99] {
            let a = r * r;
            let s = Specular {
                ndf: Ndf::new(NdfKind::Ggx, a).unwrap(),
                masking: Masking::SmithHeightCorrelated,
                fresnel: Fresnel::None,
            };
            let t = std::time::Instant::now();
            let (v, e, n) = split_sum(&s, mu, 1e-7);
            let t1 = t.elapsed();
            let t = std::time::Instant::now();
            let (c, ce, cn) = if std::env::args().count() > 1 {
                sheen_albedo(a, mu, 1e-7)
            } else {
                (0.0, 0.0, 0)
            };
            println!("mu {mu:.4} r {r:.4}: ggx {:?} {n} evals {v:?} err {e:?} | cloth {:?} {cn} {c} {ce}", t1, t.elapsed());
        }
    }
}
