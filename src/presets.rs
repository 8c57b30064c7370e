//! The default presets, compiled in so the binary works outside the repository. The files
//! in `presets/` are the source; a `presets/` directory in the working directory takes
//! precedence at run time.

/// (name, JSON text) of every built-in preset.
pub const BUILTIN: &[(&str, &str)] = &[
    (
        "cook-torrance-1982",
        include_str!("../presets/cook-torrance-1982.json"),
    ),
    (
        "energy-albedo",
        include_str!("../presets/energy-albedo.json"),
    ),
    ("filament-dfg", include_str!("../presets/filament-dfg.json")),
    ("gaussian-ndf", include_str!("../presets/gaussian-ndf.json")),
    (
        "karis-envbrdf",
        include_str!("../presets/karis-envbrdf.json"),
    ),
    ("smith-g", include_str!("../presets/smith-g.json")),
    (
        "kulla-conty-ggx",
        include_str!("../presets/kulla-conty-ggx.json"),
    ),
    (
        "fresnel-albedo",
        include_str!("../presets/fresnel-albedo.json"),
    ),
    (
        "dielectric-btdf",
        include_str!("../presets/dielectric-btdf.json"),
    ),
    (
        "sheen-charlie",
        include_str!("../presets/sheen-charlie.json"),
    ),
    (
        "classic-albedo",
        include_str!("../presets/classic-albedo.json"),
    ),
];

/// (name, JSON text) of every built-in engine preset (`presets/engines/`): each reproduces
/// one table an engine ships, on the engine's own grid, and says where the original lives.
/// Baked by name (`brdfbake bake cycles-ggx-e`), compared with `brdfbake compare`; a bare
/// `brdfbake bake` leaves them out.
pub const ENGINES: &[(&str, &str)] = &[
    (
        "babylon-env-brdf",
        include_str!("../presets/engines/babylon-env-brdf.json"),
    ),
    ("bevy-dfg", include_str!("../presets/engines/bevy-dfg.json")),
    (
        "bsdl-ggx-energy",
        include_str!("../presets/engines/bsdl-ggx-energy.json"),
    ),
    (
        "bsdl-sheen-energy",
        include_str!("../presets/engines/bsdl-sheen-energy.json"),
    ),
    (
        "cycles-ggx-e",
        include_str!("../presets/engines/cycles-ggx-e.json"),
    ),
    (
        "cycles-ggx-eavg",
        include_str!("../presets/engines/cycles-ggx-eavg.json"),
    ),
    (
        "cycles-glass-e",
        include_str!("../presets/engines/cycles-glass-e.json"),
    ),
    (
        "cycles-glass-eavg",
        include_str!("../presets/engines/cycles-glass-eavg.json"),
    ),
    (
        "cycles-ggx-gen-schlick-s",
        include_str!("../presets/engines/cycles-ggx-gen-schlick-s.json"),
    ),
    (
        "cycles-ggx-gen-schlick-ior-s",
        include_str!("../presets/engines/cycles-ggx-gen-schlick-ior-s.json"),
    ),
    (
        "cycles-glass-inv-e",
        include_str!("../presets/engines/cycles-glass-inv-e.json"),
    ),
    (
        "cycles-glass-inv-eavg",
        include_str!("../presets/engines/cycles-glass-inv-eavg.json"),
    ),
    (
        "eevee-ltc-ggx",
        include_str!("../presets/engines/eevee-ltc-ggx.json"),
    ),
    (
        "eevee-bsdf-split-sum-ggx",
        include_str!("../presets/engines/eevee-bsdf-split-sum-ggx.json"),
    ),
    (
        "eevee-brdf-ggx",
        include_str!("../presets/engines/eevee-brdf-ggx.json"),
    ),
    (
        "eevee-btdf-split-sum-ggx",
        include_str!("../presets/engines/eevee-btdf-split-sum-ggx.json"),
    ),
    (
        "eevee-bsdf-ggx",
        include_str!("../presets/engines/eevee-bsdf-ggx.json"),
    ),
    (
        "eevee-btdf-ggx",
        include_str!("../presets/engines/eevee-btdf-ggx.json"),
    ),
    (
        "godot-dfg",
        include_str!("../presets/engines/godot-dfg.json"),
    ),
    (
        "gltf-lut-charlie",
        include_str!("../presets/engines/gltf-lut-charlie.json"),
    ),
    (
        "gltf-lut-ggx",
        include_str!("../presets/engines/gltf-lut-ggx.json"),
    ),
    (
        "gltf-lut-sheen-e",
        include_str!("../presets/engines/gltf-lut-sheen-e.json"),
    ),
    (
        "learnopengl-brdf-lut",
        include_str!("../presets/engines/learnopengl-brdf-lut.json"),
    ),
    (
        "heitz-ltc",
        include_str!("../presets/engines/heitz-ltc.json"),
    ),
    (
        "materialx-albedo-table",
        include_str!("../presets/engines/materialx-albedo-table.json"),
    ),
    (
        "nvdiffrec-bsdf-256",
        include_str!("../presets/engines/nvdiffrec-bsdf-256.json"),
    ),
    (
        "threejs-dfg-lut",
        include_str!("../presets/engines/threejs-dfg-lut.json"),
    ),
    (
        "unreal-preintegrated-gf",
        include_str!("../presets/engines/unreal-preintegrated-gf.json"),
    ),
    (
        "threejs-ltc",
        include_str!("../presets/engines/threejs-ltc.json"),
    ),
];

#[cfg(test)]
mod tests {
    /// Every built-in preset parses and validates.
    #[test]
    fn builtin_presets_are_valid() {
        for (n, t) in super::BUILTIN.iter().chain(super::ENGINES) {
            crate::preset::parse(t, n, n).unwrap_or_else(|e| panic!("{n}: {e}"));
        }
    }
}
