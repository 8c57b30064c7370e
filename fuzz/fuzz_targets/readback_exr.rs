//! EXR readback (`brdfbake inspect/probe/verify x.exr`): any bytes give a Lut or an error.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.exr");
    if let Ok((lut, _facts)) = brdfbake::readback::read_exr_bytes(path, data, None) {
        let _ = brdfbake::readback::stats(&lut);
    }
});
