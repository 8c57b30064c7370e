use brdfbake::fit::{search, target};
fn main() {
    let name = std::env::args().nth(1).unwrap_or("karis-envbrdf".into());
    let (_, text) = brdfbake::presets::BUILTIN
        .iter()
        .chain(brdfbake::presets::ENGINES.iter())
        .find(|(n, _)| *n == name)
        .unwrap();
    let p = brdfbake::preset::parse(text, &name, &name).unwrap();
    let t = &p.tables[0];
    let t0 = std::time::Instant::now();
    let tg = target::build(&t.spec, None).unwrap();
    eprintln!("target {:?} in {:?}", tg.shape(), t0.elapsed());
    let t0 = std::time::Instant::now();
    let c = search::search(
        &tg,
        search::Weight::Absolute,
        true,
        &search::Limits::default(),
        &|| false,
    );
    eprintln!("search in {:?}", t0.elapsed());
    for x in &c {
        println!(
            "{:4} ops {:2} sp {:5} const  err {:.3e}  f32 {:.1e}  {}",
            x.counts.ops,
            x.counts.special,
            x.counts.constants,
            x.max_error(),
            x.f32_bound.iter().cloned().fold(0.0, f64::max),
            x.description
        );
    }
}
