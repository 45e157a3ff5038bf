//! The rolling tire's hot dense products (issue #16): `y = A x` with `Aᵀ` stored, for the
//! stacked force matrix `[G₁ H]` (682 × 341 stored, 341 outputs) and the explicit inverse of the
//! iteration matrix (341 × 341), and the same for the mirror half model (n = 173), as in one
//! tire step: `mbd_core::linalg::matvec` (several rows
//! per pass, faer's reduction order) against faer's own `matmul`, and the two-thread split
//! product (`mbd_core::parallel::SplitProduct`) against the one-thread product. Prints µs per
//! pair of products and `ratio = ours / peer`.
//! Run: `cargo bench -p mbd-core --bench matvec`.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use mbd_core::linalg::matvec;
use mbd_core::parallel::{DEFAULT_SPIN, ProductWorker, SplitProduct};
use std::sync::Arc;
use std::time::Instant;

fn faer_matvec(a: MatRef<'_, f64>, x: &[f64], out: &mut [f64]) {
    let xv = MatRef::from_column_major_slice(x, x.len(), 1);
    let ov = MatMut::from_column_major_slice_mut(out, a.nrows(), 1);
    matmul(ov, Accum::Replace, a, xv, 1.0, Par::Seq);
}

fn stored(nx: usize, ny: usize) -> Mat<f64> {
    Mat::from_fn(nx, ny, |i, j| {
        ((i * 7919 + j * 104_729) % 1000) as f64 / 997.0 - 0.5
    })
}

/// Least over `rounds` rounds of the time per call of `f` \[µs\] (the least disturbed by
/// other processes on a shared machine).
fn time(rounds: usize, reps: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..rounds)
        .map(|_| {
            let s = Instant::now();
            for _ in 0..reps {
                f();
            }
            s.elapsed().as_secs_f64() / reps as f64 * 1e6
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[0]
}

/// Alternations of the two timed variants (each timed over `rounds` rounds).
const ALTERNATIONS: usize = 5;

fn main() {
    // the mirror half model of the default tire (173 coordinates) and the full model (341);
    // `MATVEC_N=n` for another size
    let sizes: Vec<usize> = match std::env::var("MATVEC_N") {
        Ok(v) => vec![v.parse().expect("MATVEC_N: a size")],
        Err(_) => vec![173, 341],
    };
    for n in sizes {
        println!("n = {n} ({}×{n} and {n}×{n} stored):", 2 * n);
        bench(n);
    }
}

fn bench(n: usize) {
    let g = stored(2 * n, n);
    let s = stored(n, n);
    let x2: Vec<f64> = (0..2 * n).map(|i| (0.37 * i as f64).cos()).collect();
    let mut y = vec![0.0; n];
    let mut z = vec![0.0; n];
    let (rounds, reps) = (7, 1000);
    let mut faer_t = 0.0;
    let mut ours_t = 0.0;
    // alternate so that both see the same load
    for _ in 0..ALTERNATIONS {
        faer_t += time(rounds, reps, || {
            faer_matvec(g.as_ref().transpose(), &x2, &mut y);
            faer_matvec(s.as_ref().transpose(), &x2[..n], &mut z);
        });
        ours_t += time(rounds, reps, || {
            matvec(g.as_ref().transpose(), &x2, &mut y);
            matvec(s.as_ref().transpose(), &x2[..n], &mut z);
        });
    }
    println!(
        "one thread: faer {:.1} µs, linalg::matvec {:.1} µs per pair; ratio = ours / peer = {:.3}",
        faer_t / ALTERNATIONS as f64,
        ours_t / ALTERNATIONS as f64,
        ours_t / faer_t
    );
    let worker = ProductWorker::new(DEFAULT_SPIN).expect("worker thread");
    let mut pg = SplitProduct::new(Some(Arc::clone(&worker)));
    let mut ps = SplitProduct::new(Some(Arc::clone(&worker)));
    pg.set(g.as_ref());
    ps.set(s.as_ref());
    let mut one_t = 0.0;
    let mut two_t = 0.0;
    let mut w = vec![0.0; n];
    for _ in 0..ALTERNATIONS {
        one_t += time(rounds, reps, || {
            matvec(g.as_ref().transpose(), &x2, &mut y);
            matvec(s.as_ref().transpose(), &y, &mut z);
        });
        two_t += time(rounds, reps, || {
            pg.apply(g.as_ref(), &x2, &mut w);
            ps.apply(s.as_ref(), &w, &mut z);
        });
    }
    println!(
        "two threads (SplitProduct): one {:.1} µs, two {:.1} µs per pair; ratio = two / one = {:.3}",
        one_t / ALTERNATIONS as f64,
        two_t / ALTERNATIONS as f64,
        two_t / one_t
    );
}
