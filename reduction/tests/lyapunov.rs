//! The Lyapunov solver against analytic Gramians (moved from the unit tests of
//! `reduction/src/lyapunov.rs`).

use faer::Mat;
use reduction::lyapunov::lyapunov;

#[test]
fn diagonal_and_complex_pair_analytic() {
    // A = diag(−1, −2), Q = I ⇒ S = diag(1/2, 1/4) (analytic: 2 a_i s_ii + 1 = 0).
    let a = Mat::from_fn(2, 2, |i, j| if i == j { -(i as f64 + 1.0) } else { 0.0 });
    let s = lyapunov(a.as_ref(), Mat::<f64>::identity(2, 2).as_ref()).unwrap();
    assert!((s[(0, 0)] - 0.5).abs() < 1e-15 && (s[(1, 1)] - 0.25).abs() < 1e-15);
    assert!(s[(0, 1)].abs() < 1e-15);
    // damped oscillator A = [0 1; −w² −2ζw], Q = diag(0, 1): the Gramian is
    // S = diag(1/(4ζw³), 1/(4ζw)) (analytic).
    let (w, z) = (3.0, 0.05);
    let a = Mat::from_fn(2, 2, |i, j| [[0.0, 1.0], [-w * w, -2.0 * z * w]][i][j]);
    let q = Mat::from_fn(2, 2, |i, j| (i == 1 && j == 1) as u8 as f64);
    let s = lyapunov(a.as_ref(), q.as_ref()).unwrap();
    let e = [1.0 / (4.0 * z * w * w * w), 1.0 / (4.0 * z * w)];
    for i in 0..2 {
        assert!(
            (s[(i, i)] - e[i]).abs() < 1e-13 * e[i],
            "{i}: {}",
            s[(i, i)]
        );
    }
    assert!(s[(0, 1)].abs() < 1e-13);
}
