//! Matrix Market reader: any bytes give a matrix or a typed error (never a panic or an
//! allocation from the header's counts), with and without the symmetric requirement; a parsed
//! matrix converts to CSC.
#![no_main]
use fe_model::io::mtx::{ReadOptions, parse_with};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    for opts in [ReadOptions::default(), ReadOptions::symmetric()] {
        if let Ok(m) = parse_with(data, "fuzz.mtx", &opts) {
            let _ = m.to_sparse();
        }
    }
});
