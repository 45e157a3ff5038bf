//! `DofSplit` (moved from the unit tests of `fe-model/src/partition.rs`, so that the library is
//! not compiled a second time for its unit tests).

use faer::Mat;
use fe_model::DofSplit;

/// Eliminated and kept fixed DOFs give the same static solution (the kept system is the
/// eliminated one plus decoupled identity rows).
#[test]
fn eliminated_and_kept_agree() {
    use faer::linalg::solvers::Solve;
    let n = 6;
    let k = Mat::from_fn(n, n, |i, j| {
        if i == j {
            4.0
        } else if i.abs_diff(j) == 1 {
            -1.0
        } else {
            0.0
        }
    });
    let ks = fe_model::sparse::from_dense(k.as_ref(), 0.0).unwrap();
    let p = DofSplit::fixed(n, &[0, 4]).unwrap();
    assert_eq!(p.rest(), &[1, 2, 3, 5]);
    let kff = p.dense_block(k.as_ref(), false, false).unwrap();
    let f = Mat::from_fn(4, 1, |i, _| 1.0 + i as f64);
    let uf = kff.partial_piv_lu().solve(&f);
    let kept = p.keep_fixed(ks.as_ref(), 1.0).unwrap().to_dense();
    let ff = p.expand_rest(f.as_ref(), 0.0);
    let u = kept.partial_piv_lu().solve(&ff);
    let ue = p.expand_rest(uf.as_ref(), 0.0);
    for i in 0..n {
        assert!((u[(i, 0)] - ue[(i, 0)]).abs() < 1e-14);
    }
    assert!(DofSplit::fixed(3, &[5]).is_err());
}
