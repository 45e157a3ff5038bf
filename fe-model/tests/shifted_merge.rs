//! `fe_model::eigen::factor::shifted` (K − σM merged column by column) against the reference
//! it replaced: summing the triplets of K and −σM with faer's `try_new_from_triplets`. The two
//! must agree entry by entry, bit for bit, on the same pattern, for sorted and unsorted
//! columns.

use faer::sparse::{SparseColMat, SymbolicSparseColMat, Triplet};
use fe_model::eigen::factor::shifted;

/// A deterministic pseudo-random symmetric pattern with values (both triangles), `n × n`.
fn random_sym(n: usize, seed: u64, density: f64) -> Vec<Triplet<usize, usize, f64>> {
    let mut s = seed;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut t = Vec::new();
    for c in 0..n {
        t.push(Triplet::new(c, c, 4.0 + next()));
        for r in c + 1..n {
            if next() < density {
                // some stored zeros too, as in a consistent mass assembled on K's pattern
                let v = if next() < 0.3 { 0.0 } else { next() - 0.5 };
                t.push(Triplet::new(r, c, v));
                t.push(Triplet::new(c, r, v));
            }
        }
    }
    t
}

fn reference(
    k: &[Triplet<usize, usize, f64>], m: &[Triplet<usize, usize, f64>], n: usize, sigma: f64,
) -> SparseColMat<usize, f64> {
    let mut t = k.to_vec();
    t.extend(m.iter().map(|e| Triplet::new(e.row, e.col, -sigma * e.val)));
    SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
}

fn assert_same(a: &SparseColMat<usize, f64>, b: &SparseColMat<usize, f64>) {
    assert_eq!(a.symbolic().col_ptr(), b.symbolic().col_ptr());
    assert_eq!(a.symbolic().row_idx(), b.symbolic().row_idx());
    for (x, y) in a.val().iter().zip(b.val()) {
        assert_eq!(x.to_bits(), y.to_bits(), "{x} vs {y}");
    }
}

#[test]
fn merged_shift_equals_the_triplet_sum() {
    let n = 60;
    let kt = random_sym(n, 1, 0.1);
    let mt = random_sym(n, 2, 0.07);
    let k = SparseColMat::try_new_from_triplets(n, n, &kt).unwrap();
    let m = SparseColMat::try_new_from_triplets(n, n, &mt).unwrap();
    for sigma in [0.0, -3.25e-6, 1234.5] {
        let a = shifted(k.as_ref(), m.as_ref(), sigma).unwrap();
        assert_same(&a, &reference(&kt, &mt, n, sigma));
    }
}

#[test]
fn merged_shift_handles_unsorted_columns() {
    // K with its row indices reversed inside every column (a valid unsorted CSC)
    let n = 40;
    let kt = random_sym(n, 3, 0.15);
    let mt = random_sym(n, 4, 0.1);
    let ks = SparseColMat::try_new_from_triplets(n, n, &kt).unwrap();
    let (mut rows, mut vals) = (Vec::new(), Vec::new());
    let mut ptr = vec![0usize];
    for c in 0..n {
        let r: Vec<usize> = ks.as_ref().row_idx_of_col(c).collect();
        let v = ks.as_ref().val_of_col(c);
        for i in (0..r.len()).rev() {
            rows.push(r[i]);
            vals.push(v[i]);
        }
        ptr.push(rows.len());
    }
    let k = SparseColMat::new(
        SymbolicSparseColMat::new_unsorted_checked(n, n, ptr, None, rows),
        vals,
    );
    let m = SparseColMat::try_new_from_triplets(n, n, &mt).unwrap();
    let a = shifted(k.as_ref(), m.as_ref(), 7.5).unwrap();
    assert_same(&a, &reference(&kt, &mt, n, 7.5));
}
