//! Sidecar JSON (`brdfbake inspect/probe x.json`): parsed and rebuilt into a table.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(v) = serde_json::from_slice::<serde_json::Value>(data) {
        if let Ok(t) = brdfbake::readback::table_from_sidecar(&v) {
            let _ = brdfbake::meta::input_hash(&t);
        }
    }
});
