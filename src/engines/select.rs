//! `bake --engine NAME`: an engine's presets by the engine's name.
//!
//! An engine's presets are the built-in presets that name a `source` (they reproduce a
//! table that engine ships) and whose name starts with the engine's key and a hyphen
//! (`godot-dfg` → `godot`). The key is the preset names' own prefix, so a new engine preset
//! joins its engine without a list to update here; `blender` gathers Blender's two renderers
//! (`eevee-*`, `cycles-*`), and a name is matched without case and without dots (`three.js`).

use crate::preset::Preset;

/// Names that gather several keys: (name, keys).
const GROUPS: &[(&str, &[&str])] = &[("blender", &["eevee", "cycles"])];

/// Every built-in preset (default and engine presets) that reproduces an engine's table, by
/// name.
fn sourced() -> Vec<Preset> {
    crate::presets::BUILTIN
        .iter()
        .chain(crate::presets::ENGINES)
        .filter_map(|(n, t)| crate::preset::parse(t, n, n).ok())
        .filter(|p| p.source.is_some())
        .collect()
}

/// The key of a preset's name: the part before its first hyphen.
fn key_of(name: &str) -> &str {
    name.split('-').next().unwrap_or(name)
}

/// Every engine name `--engine` accepts, sorted, with the presets it bakes (sorted).
pub fn engines() -> Vec<(String, Vec<String>)> {
    let presets = sourced();
    let mut map: std::collections::BTreeMap<String, Vec<String>> = Default::default();
    for p in &presets {
        map.entry(key_of(&p.name).to_string())
            .or_default()
            .push(p.name.clone());
    }
    for (group, keys) in GROUPS {
        let mut all: Vec<String> = keys
            .iter()
            .flat_map(|k| map.get(*k).cloned().unwrap_or_default())
            .collect();
        all.sort();
        map.insert(group.to_string(), all);
    }
    map.into_iter()
        .map(|(k, mut v)| {
            v.sort();
            (k, v)
        })
        .collect()
}

/// The presets of the engine `name` (case and dots ignored), or an error that lists the
/// engines accepted.
pub fn presets_of(name: &str) -> Result<Vec<String>, String> {
    let wanted: String = name
        .chars()
        .filter(|c| *c != '.')
        .flat_map(char::to_lowercase)
        .collect();
    let all = engines();
    if let Some((_, v)) = all.iter().find(|(k, _)| *k == wanted) {
        return Ok(v.clone());
    }
    let keys: Vec<&str> = all.iter().map(|(k, _)| k.as_str()).collect();
    let hint = crate::names::did_you_mean(&wanted, keys.iter().copied())
        .map(|k| format!(" Did you mean `{k}`?"))
        .unwrap_or_default();
    Err(format!(
        "--engine {name:?}: no engine of that name.{hint} Accepted: {} (`brdfbake list` lists their presets)",
        keys.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every engine preset belongs to exactly one engine (its prefix), and each engine's
    /// presets all reproduce a shipped table (a `source`).
    #[test]
    fn every_engine_preset_has_one_engine() {
        let all = engines();
        for (n, _) in crate::presets::ENGINES {
            let owners: Vec<&str> = all
                .iter()
                .filter(|(k, v)| !GROUPS.iter().any(|(g, _)| g == k) && v.iter().any(|p| p == n))
                .map(|(k, _)| k.as_str())
                .collect();
            assert_eq!(owners.len(), 1, "{n}: engines {owners:?}");
        }
        assert_eq!(presets_of("Godot").unwrap(), vec!["godot-dfg".to_string()]);
        assert!(presets_of("three.js")
            .unwrap()
            .contains(&"threejs-ltc".to_string()));
        let blender = presets_of("blender").unwrap();
        assert!(blender.iter().any(|p| p.starts_with("eevee-")));
        assert!(blender.iter().any(|p| p.starts_with("cycles-")));
        assert!(presets_of("filament")
            .unwrap()
            .contains(&"filament-dfg".to_string()));
        let e = presets_of("godt").unwrap_err();
        assert!(e.contains("Did you mean `godot`"), "{e}");
    }
}
