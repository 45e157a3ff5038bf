//! Matrix Market reader: any bytes give a matrix or a typed error (never a panic or an
//! allocation from the header's counts), with and without the symmetric requirement; a parsed
//! matrix converts to CSC, and the straight-to-CSC reader gives the same matrix (bit for bit)
//! or the same error.
#![no_main]
use fe_model::io::mtx::{ReadOptions, parse_sparse_with, parse_with};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    for opts in [ReadOptions::default(), ReadOptions::symmetric()] {
        let two = parse_with(data, "fuzz.mtx", &opts).and_then(|m| m.to_sparse());
        let one = parse_sparse_with(data, "fuzz.mtx", &opts);
        match (one, two) {
            (Ok(a), Ok(b)) => {
                assert_eq!(a.symbolic().col_ptr(), b.symbolic().col_ptr());
                assert_eq!(a.symbolic().row_idx(), b.symbolic().row_idx());
                assert!(a.val().iter().zip(b.val()).all(|(x, y)| x.to_bits() == y.to_bits()));
            }
            (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
            (a, b) => panic!("{:?} vs {:?}", a.map(|_| ()), b.map(|_| ())),
        }
    }
});
