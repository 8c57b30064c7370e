use brdfbake::fit::{reference, search, target};
fn main() {
    let name = std::env::args().nth(1).unwrap_or("karis-envbrdf".into());
    let (_, text) = brdfbake::presets::BUILTIN
        .iter()
        .chain(brdfbake::presets::ENGINES.iter())
        .find(|(n, _)| *n == name)
        .unwrap();
    let p = brdfbake::preset::parse(text, &name, &name).unwrap();
    let t = &p.tables[0];
    let tg = target::build(&t.spec, None).unwrap();
    if std::env::var("DUMP").is_ok() {
        dump(&tg);
        check(&t.spec);
    }
    for r in reference::all() {
        if reference::preset_of(r.name) == Some(name.as_str()) {
            let m = reference::measure(&r.program, &tg);
            println!(
                "{} ops {:?} err {:?} at {:?}",
                r.name, m.counts, m.error, m.argmax
            );
        }
    }
    if std::env::args().nth(2).is_none() {
        return;
    }
    let c = search::search(
        &tg,
        search::Weight::Absolute,
        true,
        &search::Limits::default(),
        &|| false,
    );
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
#[allow(dead_code)]
fn dump(tg: &target::Target) {
    let s = tg.shape();
    for j in [0, s[1] / 8, s[1] / 2, s[1] - 1] {
        for i in [0usize, 1, 2, 4, 8, 32, s[0] - 1] {
            let k = i + s[0] * j;
            println!(
                "{:?} {:?}",
                tg.point(k),
                tg.values.iter().map(|v| v[k]).collect::<Vec<_>>()
            );
        }
    }
}
#[allow(dead_code)]
fn check(spec: &brdfbake::table::TableSpec) {
    for x in [
        [1.0, 1.0],
        [1e-6, 1.0],
        [0.5, 0.5],
        [1.0, 0.5],
        [0.125, 0.125],
    ] {
        println!("exact_at {:?} {:?}", x, target::exact_at(spec, &x, 1e-7));
    }
}
