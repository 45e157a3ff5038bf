//! The sparse path of `KktSolver` on node-block patterns, both LU variants (supernodal above
//! `SUPERNODAL_MIN_DENSITY` entries per column, faer's heuristic below), against the dense path
//! of the same solver (partial-pivoting LU of the assembled matrix, an independent
//! factorisation) and against the residual of the augmented system `[S Dᵀ; D 0] [x; μ] = [b; c]`.

use faer::sparse::Triplet;
use mbd_core::SysMatrix;
use mbd_core::linalg::{KktSolver, SUPERNODAL_MIN_DENSITY};

/// A nonsymmetric cyclic block-tridiagonal matrix (`b` coordinates per node, the pattern of a
/// closed belt loop) with a diagonally weighted value set selected by `seed`.
fn block_band(b: usize, nodes: usize, seed: usize) -> Vec<Triplet<usize, usize, f64>> {
    let mut t = Vec::new();
    for i in 0..b * nodes {
        let node = i / b;
        for nb in [node + nodes - 1, node, node + 1] {
            let nb = nb % nodes;
            for c in 0..b {
                let j = nb * b + c;
                let v = if i == j {
                    4.0 * b as f64 + (seed % 3) as f64
                } else {
                    (((i * 7 + j * 13 + seed * 5) % 11) as f64 - 5.0) / 5.0
                };
                t.push(Triplet::new(i, j, v));
            }
        }
    }
    t
}

/// Two constraint rows per `every`-th node: `x_{node·b} − x_{(node+1)·b} = …` and the second
/// coordinate fixed.
fn constraints(b: usize, nodes: usize, every: usize) -> Vec<Triplet<usize, usize, f64>> {
    let mut t = Vec::new();
    let mut row = 0;
    for node in (0..nodes).step_by(every) {
        t.push(Triplet::new(row, node * b, 1.0));
        t.push(Triplet::new(row, ((node + 1) % nodes) * b, -1.0));
        t.push(Triplet::new(row + 1, node * b + 1, 1.0));
        row += 2;
    }
    t
}

/// `‖[S Dᵀ; D 0] [x; μ] − [b; c]‖∞` with dense products.
fn residual(s: &SysMatrix, d: &SysMatrix, sol: &[f64], rhs: &[f64]) -> f64 {
    let (s, d) = (s.to_dense(), d.to_dense());
    let (n, m) = (s.nrows(), d.nrows());
    let mut worst = 0.0f64;
    for i in 0..n {
        let mut r = -rhs[i];
        for j in 0..n {
            r += s[(i, j)] * sol[j];
        }
        for k in 0..m {
            r += d[(k, i)] * sol[n + k];
        }
        worst = worst.max(r.abs());
    }
    for k in 0..m {
        let mut r = -rhs[n + k];
        for j in 0..n {
            r += d[(k, j)] * sol[j];
        }
        worst = worst.max(r.abs());
    }
    worst
}

/// Factors `S = 0.5 S + 0.5 S` (two scaled blocks, as the generalized-α matrix is assembled)
/// with `solver` and `S` densely with `dense`, and checks the solutions of one right-hand side
/// against each other and against the residual of the augmented system; returns the
/// right-hand side, `solver`'s solution and the solution's size.
fn compare(
    solver: &mut KktSolver, dense: &mut KktSolver, s_sp: &SysMatrix, d_sp: &SysMatrix, label: &str,
) -> (Vec<f64>, Vec<f64>, f64) {
    let (n, m) = (s_sp.nrows(), d_sp.nrows());
    let s_de = SysMatrix::Dense(s_sp.to_dense());
    let d_de = SysMatrix::Dense(d_sp.to_dense());
    solver
        .factor(&[(0.5, s_sp), (0.5, s_sp)], Some(d_sp), 0.0)
        .expect("sparse LU");
    dense
        .factor(&[(1.0, &s_de)], Some(&d_de), 0.0)
        .expect("dense LU");
    let rhs: Vec<f64> = (0..n + m).map(|i| ((i * 3) % 7) as f64 - 3.0).collect();
    let (mut xs, mut xd) = (rhs.clone(), rhs.clone());
    solver.solve(&mut xs, 0.0).expect("sparse solve");
    dense.solve(&mut xd, 0.0).expect("dense solve");
    let scale = xd.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let diff = xs
        .iter()
        .zip(&xd)
        .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()));
    assert!(
        diff <= 1e-12 * scale.max(1.0),
        "{label}: sparse and dense solutions differ by {diff:e} (scale {scale:e})"
    );
    let res = residual(s_sp, d_sp, &xs, &rhs);
    assert!(res <= 1e-11, "{label}: residual {res:e}");
    (rhs, xs, scale)
}

/// `supernodal`: whether the pattern of `S` is meant to lie at or above the threshold.
fn check(b: usize, nodes: usize, supernodal: bool) {
    let n = b * nodes;
    let density = block_band(b, nodes, 0).len() as f64 / n as f64;
    assert_eq!(
        density >= SUPERNODAL_MIN_DENSITY,
        supernodal,
        "{density} entries per column"
    );
    let dt = constraints(b, nodes, 4);
    let m = dt.len() / 3 * 2;
    let d_sp = SysMatrix::from_triplets(m, n, &dt, true, 0.0).expect("D");
    let mut sparse = KktSolver::new();
    let mut dense = KktSolver::new();
    // three value sets on one pattern: the symbolic analysis is made once and reused
    for seed in 0..3 {
        let st = block_band(b, nodes, seed);
        let s_sp = SysMatrix::from_triplets(n, n, &st, true, 0.0).expect("S");
        compare(&mut sparse, &mut dense, &s_sp, &d_sp, &format!("b = {b}"));
    }
    assert_eq!(sparse.symbolic_factorizations, 1);
    assert_eq!(sparse.factorizations, 3);
}

/// Six coordinates per node (planar ANCF belt): 18 pattern entries per column, above
/// `SUPERNODAL_MIN_DENSITY`: the supernodal LU.
#[test]
fn supernodal_block_pattern_matches_dense_lu() {
    check(6, 20, true);
    check(6, 60, true);
}

/// Two coordinates per node: 6 entries per column, below the threshold: faer's choice.
#[test]
fn sparse_scalar_pattern_matches_dense_lu() {
    check(2, 40, false);
}

/// `block_band` plus one border coordinate (last) coupled both ways to every coordinate of the
/// loop, as a free pulley's angle couples to every belt element that may touch it; the
/// coordinates in `isolate` keep only their (zero) diagonal and their coupling to the border
/// (the pattern is unchanged), so that the banded part alone is singular.
fn bordered(
    b: usize, nodes: usize, seed: usize, isolate: &[usize],
) -> Vec<Triplet<usize, usize, f64>> {
    let n = b * nodes;
    let mut t: Vec<_> = block_band(b, nodes, seed)
        .into_iter()
        .map(|e| {
            if isolate.contains(&e.row) || isolate.contains(&e.col) {
                Triplet::new(e.row, e.col, 0.0)
            } else {
                e
            }
        })
        .collect();
    for i in 0..n {
        let v = 0.5 + ((i * 5 + seed) % 7) as f64 / 7.0;
        t.push(Triplet::new(i, n, v));
        t.push(Triplet::new(n, i, -0.75 * v));
    }
    t.push(Triplet::new(n, n, 3.0 * n as f64));
    t
}

/// The banded-plus-border LU (`KktSolver::banded`) against the dense partial-pivoting LU of
/// the same matrix (an independent factorisation) and the residual of the augmented system:
/// the closed belt loop with a pulley border (six coordinates per node), with and without
/// constraint rows (zero diagonal of the multipliers: pivoting within the band), one and
/// several right-hand sides.
#[test]
fn banded_lu_matches_dense_lu() {
    let (b, nodes) = (6, 20);
    let n = b * nodes + 1;
    for with_d in [false, true] {
        let dt = constraints(b, nodes, 4);
        let m = if with_d { dt.len() / 3 * 2 } else { 0 };
        let d_sp =
            SysMatrix::from_triplets(m, n, if with_d { &dt } else { &[] }, true, 0.0).expect("D");
        let mut banded = KktSolver::new();
        banded.banded = true;
        let mut dense = KktSolver::new();
        for seed in 0..3 {
            let st = bordered(b, nodes, seed, &[]);
            let s_sp = SysMatrix::from_triplets(n, n, &st, true, 0.0).expect("S");
            let (rhs, xb, scale) = compare(
                &mut banded,
                &mut dense,
                &s_sp,
                &d_sp,
                &format!("D: {with_d}"),
            );
            // two right-hand sides at once: the second is the first scaled by −2
            let mut cols = faer::Mat::<f64>::from_fn(n + m, 2, |i, j| {
                rhs[i] * if j == 0 { 1.0 } else { -2.0 }
            });
            banded.solve_columns(cols.as_mut(), 0.0).expect("columns");
            for i in 0..n + m {
                assert!((cols[(i, 0)] - xb[i]).abs() <= 1e-14 * scale.max(1.0));
                assert!((cols[(i, 1)] + 2.0 * xb[i]).abs() <= 1e-14 * scale.max(1.0));
            }
        }
        assert_eq!(banded.symbolic_factorizations, 1);
        assert_eq!(banded.banded_factorizations, 3, "D: {with_d}");
    }
}

/// Three border coordinates (last) coupled weakly both ways to every loop coordinate, with
/// the border block `A₂₂ = [4 1 0; 1 0.1 3; 2 5 1]`: the border's Schur complement
/// `S = A₂₂ − A₂₁ A₁₁⁻¹ A₁₂ ≈ A₂₂` needs a row swap at its second column (after the first
/// column's elimination, 0.1 − 1/4 against 5 − 2/4), between rows whose first-column
/// multipliers differ (1/4, 1/2). The dense LU of `S` swaps whole rows (multipliers
/// included), so its solve must permute the right-hand side by every swap before the forward
/// substitution; interleaving the swaps with the substitution (the banded solve's order)
/// paired the swapped rows with each other's multipliers, gave a backward error of 1e-7 to
/// 3e-6 on the ANCF FEAD belt's Newton matrices, and every such factorisation was rejected
/// and went to faer's LU (issue 37 item 4). Reference: the dense partial-pivoting LU of the
/// whole matrix (`compare`); the banded LU must factor all three value sets itself.
#[test]
fn banded_lu_pivots_the_border_schur_complement() {
    let (b, nodes) = (6, 20);
    let n = b * nodes;
    let a22 = [[4.0, 1.0, 0.0], [1.0, 0.1, 3.0], [2.0, 5.0, 1.0]];
    let d_sp = SysMatrix::from_triplets(0, n + 3, &[], true, 0.0).expect("no constraints");
    let mut banded = KktSolver::new();
    banded.banded = true;
    let mut dense = KktSolver::new();
    for seed in 0..3 {
        let mut st = block_band(b, nodes, seed);
        for (k, row) in a22.iter().enumerate() {
            for i in 0..n {
                let v = 1e-3 * (1.0 + ((i * 5 + k * 3 + seed) % 7) as f64 / 7.0);
                st.push(Triplet::new(i, n + k, v));
                st.push(Triplet::new(n + k, i, -0.5 * v));
            }
            for (c, &v) in row.iter().enumerate() {
                st.push(Triplet::new(n + k, n + c, v));
            }
        }
        let s_sp = SysMatrix::from_triplets(n + 3, n + 3, &st, true, 0.0).expect("S");
        compare(
            &mut banded,
            &mut dense,
            &s_sp,
            &d_sp,
            &format!("seed {seed}"),
        );
    }
    assert_eq!(
        (banded.banded_factorizations, banded.banded_rejections),
        (3, 0)
    );
}

/// A matrix whose banded part is singular (coordinates coupled only to the border) but
/// which is regular as a whole: the banded LU meets a zero pivot and the factorisation falls
/// back to faer's sparse LU, whose solution matches the dense LU's.
#[test]
fn banded_lu_falls_back_at_a_zero_pivot() {
    let (b, nodes) = (6, 20);
    let n = b * nodes + 1;
    // coordinate 37 (node 6) stays in the band: the loop is cut elsewhere (the count of
    // banded factorisations below checks that the fallback did happen)
    let st = bordered(b, nodes, 1, &[37]);
    let s_sp = SysMatrix::from_triplets(n, n, &st, true, 0.0).expect("S");
    let d_sp = SysMatrix::from_triplets(0, n, &[], true, 0.0).expect("no constraints");
    let mut banded = KktSolver::new();
    banded.banded = true;
    let mut dense = KktSolver::new();
    compare(&mut banded, &mut dense, &s_sp, &d_sp, "fallback");
    assert_eq!(banded.banded_factorizations, 0);
    assert_eq!(banded.factorizations, 1);
}

/// A matrix whose banded part has a tiny but nonzero pivot (a coordinate coupled only to the
/// border, with diagonal 1e-12): no zero pivot stops the banded LU, but eliminating on it
/// grows the factors by 1e12 (the 2 × 2 example of Golub & Van Loan, §3.4.1), so its solve
/// has a backward error near 1e-4. The check (`BAND_BACKWARD_ERROR_LIMIT`) rejects both band
/// plans at the first factorisation and the pattern keeps faer's LU, whose solution matches
/// the dense LU's; later factorisations of the pattern do not try the band again. Without
/// the check this is the failure that tripled the plate belt's Newton iterations (issue 37).
#[test]
fn inaccurate_banded_factors_fall_back_for_the_pattern() {
    let (b, nodes) = (6, 20);
    let n = b * nodes + 1;
    let d_sp = SysMatrix::from_triplets(0, n, &[], true, 0.0).expect("no constraints");
    let mut banded = KktSolver::new();
    banded.banded = true;
    let mut dense = KktSolver::new();
    for seed in 0..3 {
        let mut st = bordered(b, nodes, seed, &[37]);
        st.push(Triplet::new(37, 37, 1e-12));
        let s_sp = SysMatrix::from_triplets(n, n, &st, true, 0.0).expect("S");
        compare(
            &mut banded,
            &mut dense,
            &s_sp,
            &d_sp,
            &format!("seed {seed}"),
        );
    }
    assert_eq!(banded.banded_factorizations, 0);
    assert!(banded.banded_rejections >= 1);
    let after_first = banded.banded_rejections;
    assert_eq!(banded.factorizations, 3);
    // the rejections all happened at the first factorisation (one per band plan)
    assert!(after_first <= 2, "{after_first} rejections");
    // the well-conditioned matrix of the same pattern passes the check in a new solver
    let st = bordered(b, nodes, 0, &[]);
    let s_sp = SysMatrix::from_triplets(n, n, &st, true, 0.0).expect("S");
    let mut fresh = KktSolver::new();
    fresh.banded = true;
    compare(&mut fresh, &mut dense, &s_sp, &d_sp, "regular");
    assert_eq!(
        (fresh.banded_factorizations, fresh.banded_rejections),
        (1, 0)
    );
}

/// `SysMatrix::without_zeros` (the stepper's `M v̇` product): the same products `A x` and
/// `y + s A x` as the dense matrix (an independent product), with fewer stored entries.
#[test]
fn product_without_stored_zeros_matches_dense_product() {
    let st: Vec<_> = bordered(6, 20, 2, &[])
        .into_iter()
        .map(|e| {
            // zero half of the entries, as the mass on the tangent's pattern
            let keep = (e.row + e.col) % 2 == 0;
            Triplet::new(e.row, e.col, if keep { e.val } else { 0.0 })
        })
        .collect();
    let n = 121;
    let a = SysMatrix::from_triplets(n, n, &st, true, 0.0).expect("A");
    let c = a.without_zeros();
    let (mut na, mut nc) = (0, 0);
    a.for_each_entry(|_, _, _| na += 1);
    c.for_each_entry(|_, _, _| nc += 1);
    assert!(nc < na, "{nc} of {na} entries kept");
    let d = a.to_dense();
    let x: Vec<f64> = (0..n).map(|i| ((i * 5) % 9) as f64 - 4.0).collect();
    let mut y = vec![0.0; n];
    c.mul_vec(&x, &mut y);
    let mut z: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let z0 = z.clone();
    c.mul_vec_add(-0.5, &x, &mut z);
    for i in 0..n {
        let exact: f64 = (0..n).map(|j| d[(i, j)] * x[j]).sum();
        assert!(
            (y[i] - exact).abs() <= 1e-12 * exact.abs().max(1.0),
            "row {i}"
        );
        assert!((z[i] - (z0[i] - 0.5 * exact)).abs() <= 1e-12 * z0[i].abs().max(1.0));
    }
}
