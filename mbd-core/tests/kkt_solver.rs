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
    let d_de = SysMatrix::Dense(d_sp.to_dense());
    let mut sparse = KktSolver::new();
    let mut dense = KktSolver::new();
    // three value sets on one pattern: the symbolic analysis is made once and reused
    for seed in 0..3 {
        let st = block_band(b, nodes, seed);
        let s_sp = SysMatrix::from_triplets(n, n, &st, true, 0.0).expect("S");
        let s_de = SysMatrix::Dense(s_sp.to_dense());
        // S = 0.5 A + 0.5 A as two scaled blocks, as the generalized-α matrix is assembled
        sparse
            .factor(&[(0.5, &s_sp), (0.5, &s_sp)], Some(&d_sp), 0.0)
            .expect("sparse LU");
        dense
            .factor(&[(1.0, &s_de)], Some(&d_de), 0.0)
            .expect("dense LU");
        let rhs: Vec<f64> = (0..n + m).map(|i| ((i * 3) % 7) as f64 - 3.0).collect();
        let (mut xs, mut xd) = (rhs.clone(), rhs.clone());
        sparse.solve(&mut xs, 0.0).expect("sparse solve");
        dense.solve(&mut xd, 0.0).expect("dense solve");
        let scale = xd.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let diff = xs
            .iter()
            .zip(&xd)
            .fold(0.0f64, |a, (p, q)| a.max((p - q).abs()));
        assert!(
            diff <= 1e-12 * scale.max(1.0),
            "b = {b}: sparse and dense solutions differ by {diff:e} (scale {scale:e})"
        );
        let res = residual(&s_sp, &d_sp, &xs, &rhs);
        assert!(res <= 1e-11, "b = {b}: residual {res:e}");
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
