//! Physical checks of imported K and M (issue #20: an all-zero K gave −7.5·10⁻¹⁵⁹ Hz, an
//! indefinite K 0 Hz). References: the definiteness of small matrices whose eigenvalues are
//! known analytically.

use faer::sparse::{SparseColMat, Triplet};
use fe_model::FeError;
use fe_model::plausibility::{PairCheckOptions, check_stiffness_mass};

fn sparse(n: usize, t: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
    let t: Vec<_> = t.iter().map(|&(r, c, v)| Triplet::new(r, c, v)).collect();
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
}

/// A 3-spring chain K = tridiag(−1, 2, −1) (eigenvalues 2 − 2cos(kπ/4) > 0) with M = I.
fn chain(n: usize) -> Vec<(usize, usize, f64)> {
    let mut t = Vec::new();
    for i in 0..n {
        t.push((i, i, 2.0));
        if i + 1 < n {
            t.push((i + 1, i, -1.0));
            t.push((i, i + 1, -1.0));
        }
    }
    t
}

fn eye(n: usize) -> SparseColMat<usize, f64> {
    sparse(n, &(0..n).map(|i| (i, i, 1.0)).collect::<Vec<_>>())
}

fn reason(r: Result<Vec<String>, FeError>) -> (String, String) {
    match r {
        Err(FeError::Implausible { matrix, reason }) => (matrix, reason),
        other => panic!("expected Implausible, got {other:?}"),
    }
}

#[test]
fn definite_and_semidefinite_pairs_pass() {
    let opts = PairCheckOptions::default();
    // positive definite chain
    assert!(
        check_stiffness_mass(sparse(3, &chain(3)).as_ref(), eye(3).as_ref(), &opts)
            .unwrap()
            .is_empty()
    );
    // free–free chain K = [[1, −1], [−1, 1]] (eigenvalues 0 and 2: semi-definite, allowed)
    let ff = sparse(2, &[(0, 0, 1.0), (1, 0, -1.0), (0, 1, -1.0), (1, 1, 1.0)]);
    assert!(check_stiffness_mass(ff.as_ref(), eye(2).as_ref(), &opts).is_ok());
}

#[test]
fn zero_indefinite_and_massless_are_named() {
    let opts = PairCheckOptions::default();
    // all-zero K
    let (m, r) = reason(check_stiffness_mass(
        sparse(2, &[(0, 0, 0.0), (1, 1, 0.0)]).as_ref(),
        eye(2).as_ref(),
        &opts,
    ));
    assert_eq!(m, "K");
    assert!(r.contains("every entry is zero"), "{r}");
    // K = [[1, −3], [−3, 1]]: eigenvalues −2 and 4 (indefinite), positive diagonal
    let ind = sparse(2, &[(0, 0, 1.0), (1, 0, -3.0), (0, 1, -3.0), (1, 1, 1.0)]);
    let (m, r) = reason(check_stiffness_mass(ind.as_ref(), eye(2).as_ref(), &opts));
    assert_eq!(m, "K");
    assert!(r.contains("indefinite: 1 eigenvalue"), "{r}");
    // negative diagonal at DOF 2 (1-based)
    let mut t = chain(3);
    t.iter_mut()
        .filter(|e| e.0 == 1 && e.1 == 1)
        .for_each(|e| e.2 = -2.0);
    let (_, r) = reason(check_stiffness_mass(
        sparse(3, &t).as_ref(),
        eye(3).as_ref(),
        &opts,
    ));
    assert!(
        r.contains("negative diagonal") && r.ends_with("DOFs 2"),
        "{r}"
    );
    // zero diagonal coupled to another DOF (principal minor [[0, −1], [−1, 2]] < 0)
    let mut t = chain(3);
    t.iter_mut()
        .filter(|e| e.0 == 0 && e.1 == 0)
        .for_each(|e| e.2 = 0.0);
    let (_, r) = reason(check_stiffness_mass(
        sparse(3, &t).as_ref(),
        eye(3).as_ref(),
        &opts,
    ));
    assert!(
        r.contains("zero diagonal with off-diagonal") && r.ends_with("DOFs 1"),
        "{r}"
    );
    // massless DOF 3: an error for an eigen solve, a warning for a reduction
    let m3 = sparse(3, &[(0, 0, 1.0), (1, 1, 1.0), (2, 2, 0.0)]);
    let k3 = sparse(3, &chain(3));
    let (m, r) = reason(check_stiffness_mass(k3.as_ref(), m3.as_ref(), &opts));
    assert_eq!(m, "M");
    assert!(r.contains("no mass") && r.contains("DOFs 3"), "{r}");
    let w = check_stiffness_mass(
        k3.as_ref(),
        m3.as_ref(),
        &PairCheckOptions {
            massless_dofs_allowed: true,
        },
    )
    .unwrap();
    assert_eq!(w.len(), 1, "{w:?}");
    // indefinite M with a positive diagonal: [[1, 2], [2, 1]] (eigenvalues −1, 3)
    let mi = sparse(2, &[(0, 0, 1.0), (1, 0, 2.0), (0, 1, 2.0), (1, 1, 1.0)]);
    let e = check_stiffness_mass(sparse(2, &chain(2)).as_ref(), mi.as_ref(), &opts).unwrap_err();
    assert!(matches!(e, FeError::NotPositiveDefinite { .. }), "{e}");
    assert!(e.to_string().contains("pivot at DOF"), "{e}");
    // a DOF without stiffness is a warning (it moves freely)
    let kfree = sparse(2, &[(0, 0, 1.0)]);
    let w = check_stiffness_mass(kfree.as_ref(), eye(2).as_ref(), &opts).unwrap();
    assert!(w[0].contains("no stiffness at DOFs 2"), "{w:?}");
}
