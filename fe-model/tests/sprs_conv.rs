//! The sprs edge conversion (moved from the unit tests of `fe-model/src/io/sprs_conv.rs`;
//! with the `sprs` feature only).

use fe_model::io::sprs_conv::{from_sprs, to_sprs};

/// Round trip faer → sprs → faer reproduces the matrix (CSR input too).
#[test]
fn round_trip() {
    let mut tri = sprs::TriMat::new((3, 4));
    tri.add_triplet(0, 0, 1.5);
    tri.add_triplet(2, 3, -2.0);
    tri.add_triplet(1, 2, 4.0);
    tri.add_triplet(1, 2, 1.0); // duplicate: summed
    let csr: sprs::CsMat<f64> = tri.to_csr();
    let f = from_sprs(&csr).unwrap();
    let d = f.to_dense();
    assert_eq!(d[(1, 2)], 5.0);
    assert_eq!(d[(2, 3)], -2.0);
    let back = from_sprs(&to_sprs(f.as_ref())).unwrap().to_dense();
    assert_eq!(back, d);
}
