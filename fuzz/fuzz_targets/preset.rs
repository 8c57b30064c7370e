//! Preset JSON (`brdfbake bake PRESET`): any bytes must give Ok or an error, never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // `preset::load` rejects non-UTF-8 before parsing; the parser itself sees text.
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(p) = brdfbake::preset::parse(text, "fuzz.json", "fuzz") {
            // an accepted preset's metadata must be computable without panicking
            for t in &p.tables {
                let _ = brdfbake::meta::input_hash(t);
            }
        }
    }
});
