//! The default presets' tables (the presets built into the binary), for the tests that must
//! cover every one of them.

#![allow(dead_code)]

use brdfbake::lut::Lut;
use brdfbake::preset::PresetTable;

/// (preset name, table) of every table of every built-in preset, in preset order.
pub fn tables() -> Vec<(String, PresetTable)> {
    brdfbake::presets::BUILTIN
        .iter()
        .flat_map(|(name, text)| {
            let preset = brdfbake::preset::parse(text, name, name)
                .unwrap_or_else(|e| panic!("built-in preset {name}: {e}"));
            preset
                .tables
                .into_iter()
                .map(move |t| (name.to_string(), t))
        })
        .collect()
}

/// A table of `t`'s axes and channels with placeholder texels: what the encoders that depend
/// only on the table's shape (the shader snippets) need, without baking it.
pub fn shaped_lut(t: &PresetTable) -> Lut {
    let channels = brdfbake::table::channels(&t.spec);
    let texels: usize = t.spec.axes.iter().map(|a| a.size).product();
    Lut {
        axes: t.spec.axes.clone(),
        data: vec![0.5; texels * channels.len()],
        error_estimate: vec![0.0; channels.len()],
        channels,
        evaluations: 0,
    }
}
