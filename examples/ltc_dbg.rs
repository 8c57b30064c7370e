use brdfbake::kernels::ltc_check::*;
use brdfbake::kernels::ltc_fit::*;
use brdfbake::model::{Brdf, Fresnel, Masking, Ndf, NdfKind, Specular};
fn main() {
    let a: Vec<String> = std::env::args().collect();
    if a[1] == "scan" { scan(a[2].parse().unwrap(), a[3].parse().unwrap()); return; }
    if a[1] == "cmp" { let ls: Vec<usize> = a[4..].iter().map(|x| x.parse().unwrap()).collect(); compare(a[2].parse().unwrap(), a[3].parse().unwrap(), &ls); return; }
    if a[1] == "line" { line(a[2].parse().unwrap(), a[3].parse().unwrap()); return; }
    let mu: f64 = a[1].parse().unwrap(); let r: f64 = a[2].parse().unwrap();
    let en: f64 = a[3].parse().unwrap();
    let lights: Vec<usize> = a[4..].iter().map(|x| x.parse().unwrap()).collect();
    let alpha = r*r;
    let brdf = Brdf { specular: Some(Specular { ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(), masking: Masking::SmithHeightCorrelated, fresnel: Fresnel::None }), diffuse_weight: 0.0 };
    let opts = LtcFitOptions { energy_weight: en, probe_weight: std::env::var("PROBE").map(|x| x.parse().unwrap()).unwrap_or(1.0), ..Default::default() };
    let shape = opts.shape();
    let t = fit_texel(&brdf, mu, None, &shape, &opts).unwrap();
    println!("fit {:?}", t);
    let v = view_vector(mu);
    let ls = test_lights();
    for li in lights {
        let l = &ls[li];
        let m = l.verts.iter().fold([0.0;3], |a, v| { let n=(v[0]*v[0]+v[1]*v[1]+v[2]*v[2]).sqrt(); [a[0]+v[0]/n, a[1]+v[1]/n, a[2]+v[2]/n]});
        let n=(m[0]*m[0]+m[1]*m[1]+m[2]*m[2]).sqrt(); let c=[m[0]/n,m[1]/n,m[2]/n];
        let y = brdf.eval(v, c)*c[2]/t.norm; let x = t.ltc.eval(c);
        println!("light {li}: center {:?} az {:.1}deg el {:.1}deg  y {y:e}  D {x:e}", c, c[1].atan2(c[0]).to_degrees(), c[2].asin().to_degrees());
        let tr = lit_reference(&brdf, alpha, mu, l, 1e-7).unwrap();
        println!("   truth {:e} ltc {:e}", tr.value, lit_ltc(&t.ltc, t.norm, l).unwrap());
    }
    // profile along the horizon at elevation 5 deg for azimuths
    for el in [2.0f64, 10.0, 30.0] { 
      let mut s = format!("el {el}: ");
      for az in (0..=12).map(|k| k as f64 * 15.0) {
        let (e, p) = (el.to_radians(), az.to_radians());
        let w = [e.cos()*p.cos(), e.cos()*p.sin(), e.sin()];
        let y = brdf.eval(v, w)*w[2]/t.norm; let x = t.ltc.eval(w);
        s += &format!("{az}:{:.1e}/{:.1e} ", y, x);
      }
      println!("{s}");
    }
}
#[allow(dead_code)]
pub fn line(r: f64, en: f64) {
    let alpha = (r*r).max(1e-5);
    let brdf = Brdf { specular: Some(Specular { ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(), masking: Masking::SmithHeightCorrelated, fresnel: Fresnel::None }), diffuse_weight: 0.0 };
    let opts = LtcFitOptions { energy_weight: en, probe_weight: std::env::var("PROBE").map(|x| x.parse().unwrap()).unwrap_or(1.0), ..Default::default() };
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
    let alpha = (r*r).max(1e-5);
    let brdf = Brdf { specular: Some(Specular { ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(), masking: Masking::SmithHeightCorrelated, fresnel: Fresnel::None }), diffuse_weight: 0.0 };
    let opts = LtcFitOptions { probe_weight: std::env::var("PROBE").map(|x| x.parse().unwrap()).unwrap_or(1.0), ..Default::default() };
    let shape = opts.shape();
    let t = fit_texel(&brdf, mu, None, &shape, &opts).unwrap();
    println!("{:?}", t);
    let v = view_vector(mu);
    // dense scan
    let mut worst = (0.0, 0.0, 0.0);
    let mut wsum = 0.0; let mut leak = 0.0;
    for i in 0..400 { for j in 0..800 {
        let el = (i as f64 + 0.5) / 400.0 * std::f64::consts::FRAC_PI_2;
        let az = (j as f64 + 0.5) / 800.0 * 2.0 * std::f64::consts::PI;
        let w = [el.cos()*az.cos(), el.cos()*az.sin(), el.sin()];
        let y = brdf.eval(v, w)*w[2]/t.norm; let x = t.ltc.eval(w);
        let da = el.cos() * (std::f64::consts::FRAC_PI_2/400.0) * (2.0*std::f64::consts::PI/800.0);
        if x > 3.0*y { leak += x*da; }
        wsum += x*da;
        if x / (y + 1e-9) > worst.0 { worst = (x/(y+1e-9), el.to_degrees(), az.to_degrees()); }
    }}
    println!("max ratio {:.3e} at el {:.2} az {:.1}; LTC mass where x>3y: {leak:.4} of {wsum:.4}", worst.0, worst.1, worst.2);
    let rule = brdfbake::kernels::ltc_rule::HemisphereRule::new(&shape, mu, brdfbake::hemisphere::LobeWarp::TanOverScale(alpha));
    let mut wr = (0.0, 0.0, 0.0);
    for d in &rule.dirs { let y = brdf.eval(v, *d)*d[2]/t.norm; let x = t.ltc.eval(*d); if x/(y+1e-9) > wr.0 { wr = (x/(y+1e-9), d[2].asin().to_degrees(), d[1].atan2(d[0]).to_degrees()); } }
    println!("rule max ratio {:.3e} at el {:.2} az {:.1}", wr.0, wr.1, wr.2);
}
#[allow(dead_code)]
pub fn compare(mu: f64, r: f64, lights: &[usize]) {
    let alpha = (r*r).max(1e-5);
    let brdf = Brdf { specular: Some(Specular { ndf: Ndf::new(NdfKind::Ggx, alpha).unwrap(), masking: Masking::SmithHeightCorrelated, fresnel: Fresnel::None }), diffuse_weight: 0.0 };
    let opts = LtcFitOptions::default();
    let t = fit_texel(&brdf, mu, None, &opts.shape(), &opts).unwrap();
    let js = brdfbake::table::ltc_layout::HeitzTable::from_js(include_str!("../tests/data/ltc/heitz_ltc.js")).unwrap();
    let (h, hn, _) = js.ltc_at(mu, r).unwrap();
    println!("ours {:?} norm {}\nheitz {:?} norm {hn}", t.ltc, t.norm, h);
    let v = view_vector(mu);
    println!("plane of incidence, mirror side (az 180) then view side (az 0): el: y / ours / heitz");
    for az in [180.0f64, 0.0] { for el in [1.0f64, 3.0, 6.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0, 45.0, 50.0, 60.0, 70.0, 80.0, 89.0] {
        let (e, p) = (el.to_radians(), az.to_radians());
        let w = [e.cos()*p.cos(), e.cos()*p.sin(), e.sin()];
        let y = brdf.eval(v, w)*w[2]/t.norm;
        println!("  az {az} el {el}: {y:.3e} {:.3e} {:.3e}", t.ltc.eval(w), h.eval(w));
    }}
    let ls = test_lights();
    for &li in lights {
        let l = &ls[li];
        let tr = lit_reference(&brdf, alpha, mu, l, 1e-7).unwrap().value;
        println!("light {li}: verts {:?}\n   truth {tr:.4e} ours {:.4e} heitz {:.4e}", l.verts, lit_ltc(&t.ltc, t.norm, l).unwrap(), lit_ltc(&h, hn, l).unwrap());
    }
}
