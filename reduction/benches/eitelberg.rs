//! Benchmark: the Lyapunov solve of Eitelberg's method (Lin Appendix C), dense Kronecker form
//! (O(n⁶)) vs Bartels–Stewart on the complex Schur form (O(n³)), and Eitelberg's whole
//! structural reduction (Lin §6.6.4) on free-free spring-mass chains with output feedback.
//! Prints one timing per case (best of 3) and the relative residual; figures go into
//! BENCHMARKS.md.
//!
//! Run: `cargo bench -p reduction --bench eitelberg`.

use faer::Mat;
use reduction::eitelberg::{LyapunovSolver, eitelberg_structure_with, lyapunov_kronecker};
use reduction::lyapunov::lyapunov;
use std::time::Instant;

/// Free-free chain of `n` masses \[kg\] and springs \[N/m\] with a deterministic ±30 % variation.
fn chain(n: usize) -> (Mat<f64>, Mat<f64>) {
    let var = |i: usize| 1.0 + 0.6 * ((i as f64 * 1.618_033_988_7).fract() - 0.5);
    let mut k = Mat::<f64>::zeros(n, n);
    let mut m = Mat::<f64>::zeros(n, n);
    for i in 0..n {
        m[(i, i)] = var(3 * i + 1);
    }
    for e in 0..n - 1 {
        let ke = 1e4 * var(7 * e + 2);
        k[(e, e)] += ke;
        k[(e + 1, e + 1)] += ke;
        k[(e, e + 1)] -= ke;
        k[(e + 1, e)] -= ke;
    }
    (k, m)
}

/// Output-feedback state matrix `A − B L C` and `Q = (A⁻¹B)(A⁻¹B)ᵀ` (Lin §6.6.4).
fn system(n: usize, every: usize) -> (Mat<f64>, Mat<f64>) {
    let (k, m) = chain(n);
    let bd: Vec<usize> = (0..n).step_by(every).collect();
    let minv = Mat::from_fn(n, n, |i, j| if i == j { 1.0 / m[(i, i)] } else { 0.0 });
    let mk = &minv * &k;
    let mut a = Mat::<f64>::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -mk[(i, j)];
        }
    }
    let b = Mat::from_fn(2 * n, bd.len(), |i, j| {
        if i >= n && i - n == bd[j] {
            minv[(bd[j], bd[j])]
        } else {
            0.0
        }
    });
    for (jb, &d) in bd.iter().enumerate() {
        for i in 0..2 * n {
            a[(i, d)] -= b[(i, jb)];
            a[(i, n + d)] -= b[(i, jb)];
        }
    }
    let p = reduction::linalg::solve_general("A P = B", a.as_ref(), b.as_ref()).expect("A P = B");
    let q = &p * p.transpose();
    (a, q)
}

fn best_of<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..runs {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("at least one run"))
}

fn residual(a: &Mat<f64>, s: &Mat<f64>, q: &Mat<f64>) -> f64 {
    let r = a * s + s * a.transpose() + q;
    let mx = |x: &Mat<f64>| {
        let mut v = 0.0f64;
        for j in 0..x.ncols() {
            for i in 0..x.nrows() {
                v = v.max(x[(i, j)].abs());
            }
        }
        v
    };
    mx(&r) / (2.0 * mx(a) * mx(s) + mx(q))
}

fn main() {
    println!("| DOF | states | Kronecker | Bartels–Stewart | BS residual |");
    println!("|---|---|---|---|---|");
    for n in [12usize, 24, 100, 200, 300] {
        let (a, q) = system(n, 6);
        let kr = if 2 * n <= reduction::eitelberg::MAX_LYAPUNOV_STATES {
            let (t, _) = best_of(3, || {
                lyapunov_kronecker(a.as_ref(), q.as_ref()).expect("kron")
            });
            format!("{t:.4} s")
        } else {
            "— (limit 48 states)".into()
        };
        let (t, s) = best_of(3, || lyapunov(a.as_ref(), q.as_ref()).expect("bs"));
        println!(
            "| {n} | {} | {kr} | {t:.4} s | {:.1e} |",
            2 * n,
            residual(&a, &s, &q)
        );
    }
    let n = 200;
    let (k, m) = chain(n);
    let bd: Vec<usize> = (0..n).step_by(10).collect();
    let (t, _) = best_of(1, || {
        eitelberg_structure_with(k.as_ref(), m.as_ref(), &bd, LyapunovSolver::BartelsStewart)
            .expect("eitelberg")
    });
    println!(
        "\nEitelberg structure reduction, {n} DOFs, {} boundary DOFs: {t:.3} s",
        bd.len()
    );
}
