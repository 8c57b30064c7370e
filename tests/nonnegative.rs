//! A quantity that cannot be negative is never stored negative: every channel
//! `brdfbake::table::nonnegative_channels` names holds no value below 0 (nor −0) in any
//! default preset's table or in the engine presets that bake in under a second. Before the
//! clamp, filament-dfg's cloth channel held 377 texels near −5e-9 (a quadrature sum's rounding
//! next to a zero, within its error estimate).

#[test]
fn nonnegative_quantities_are_never_stored_negative() {
    let engines = [
        "cycles-ggx-e",
        "threejs-dfg-lut",
        "bsdl-ggx-energy",
        "eevee-bsdf-split-sum-ggx",
        "unreal-preintegrated-gf",
        "heitz-ltc",
    ];
    let presets = brdfbake::presets::BUILTIN.iter().chain(
        brdfbake::presets::ENGINES
            .iter()
            .filter(|(n, _)| engines.contains(n)),
    );
    let mut checked = 0;
    for (name, text) in presets {
        let preset = brdfbake::preset::parse(text, name, name).unwrap();
        for t in &preset.tables {
            let lut = brdfbake::table::bake(&t.spec).unwrap();
            let keep = brdfbake::table::nonnegative_channels(&t.spec);
            assert_eq!(keep.len(), lut.channels.len(), "{name}/{}", t.spec.name);
            let nc = lut.channels.len();
            for (i, v) in lut.data.iter().enumerate() {
                if keep[i % nc] {
                    assert!(
                        !v.is_sign_negative(),
                        "{name}/{} channel {}: texel {} holds {v}",
                        t.spec.name,
                        lut.channels[i % nc].name,
                        i / nc
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 100_000, "{checked} values checked");
}
