//! ABAQUS matrix reader: any text parses to entries or a typed error; parsed entries assemble
//! (mirrored one-triangle storage) or give a typed error.
#![no_main]
use fe_model::io::abaqus;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(e) = abaqus::parse(text, "fuzz_STIF1.mtx") {
            let _ = abaqus::assemble(&[&e]);
        }
    }
});
