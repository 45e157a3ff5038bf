//! The contact step's free-slip products `(T_c ż)ᵢ`, `(T_c,θ z)ᵢ` (six dot products of length
//! n_z per pressed node), compiled twice: for the baseline x86-64 target (SSE2) and with AVX2
//! intrinsics (one register of four partial sums per product), chosen at run time
//! (`is_x86_feature_detected!`, cached by std) like faer's kernels. Neither version fuses a
//! multiply and an add, and each output is formed by the same operations in the same order in
//! both, so the results are bitwise the same on any x86-64 machine. (The contact solver's
//! column kernels are mbd-core's, [`mbd_core::linalg::axpy_cols`].)

/// Whether the AVX2 version may run on this machine.
#[cfg(target_arch = "x86_64")]
#[inline]
fn avx2() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
}

/// The dot products `aₖ · b` of three slices with one of equal length in one pass, each with
/// four partial sums over the chunks of four (per product: `(s₀ + s₁) + (s₂ + s₃) + tail`).
#[inline(always)]
fn dots3_body(a: [&[f64]; 3], b: &[f64]) -> [f64; 3] {
    let mut acc = [[0.0; 4]; 3];
    let chunks = a[0]
        .chunks_exact(4)
        .zip(a[1].chunks_exact(4))
        .zip(a[2].chunks_exact(4))
        .zip(b.chunks_exact(4));
    for (((x0, x1), x2), y) in chunks {
        for k in 0..4 {
            acc[0][k] += x0[k] * y[k];
            acc[1][k] += x1[k] * y[k];
            acc[2][k] += x2[k] * y[k];
        }
    }
    let body = b.len() - b.len() % 4;
    let mut out = [0.0; 3];
    for (p, o) in out.iter_mut().enumerate() {
        let tail: f64 = a[p][body..]
            .iter()
            .zip(&b[body..])
            .map(|(x, y)| x * y)
            .sum();
        let c = &acc[p];
        *o = (c[0] + c[1]) + (c[2] + c[3]) + tail;
    }
    out
}

/// The two triples of dot products `aₚ · b` and `cₚ · d` (all slices of the length of `b`) in
/// one pass: six independent accumulation chains. Per product the same operations in the same
/// order as the earlier three-product kernel (four partial sums over the chunks of four, then
/// `(s₀ + s₁) + (s₂ + s₃) + tail`), so each result is bitwise the same; the AVX2
/// version holds each product's four partial sums in one register (a multiply, then an add:
/// no fused multiply-add).
pub(super) fn dots3x2(a: [&[f64]; 3], b: &[f64], c: [&[f64]; 3], d: &[f64]) -> [[f64; 3]; 2] {
    let n = b.len();
    assert!(d.len() == n && a.iter().chain(&c).all(|x| x.len() == n));
    #[cfg(target_arch = "x86_64")]
    {
        if avx2() {
            // SAFETY: AVX2 is available (checked at run time); all slices have length n
            return unsafe { dots3x2_avx2(a, b, c, d) };
        }
    }
    [dots3_body(a, b), dots3_body(c, d)]
}

/// [`dots3x2`] with AVX2 registers (lengths checked by the caller).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn dots3x2_avx2(a: [&[f64]; 3], b: &[f64], c: [&[f64]; 3], d: &[f64]) -> [[f64; 3]; 2] {
    use std::arch::x86_64::{
        __m256d, _mm256_add_pd, _mm256_loadu_pd, _mm256_mul_pd, _mm256_setzero_pd, _mm256_storeu_pd,
    };
    let n = b.len();
    let body = n - n % 4;
    let mut acc: [__m256d; 6] = [_mm256_setzero_pd(); 6];
    let cols = [a[0], a[1], a[2], c[0], c[1], c[2]];
    let mut i = 0;
    while i < body {
        // SAFETY: i + 4 ≤ body ≤ n = the length of every slice
        unsafe {
            let yb = _mm256_loadu_pd(b.as_ptr().add(i));
            let yd = _mm256_loadu_pd(d.as_ptr().add(i));
            for p in 0..6 {
                let y = if p < 3 { yb } else { yd };
                let x = _mm256_loadu_pd(cols[p].as_ptr().add(i));
                acc[p] = _mm256_add_pd(acc[p], _mm256_mul_pd(x, y));
            }
        }
        i += 4;
    }
    let mut out = [[0.0; 3]; 2];
    for p in 0..6 {
        let mut s = [0.0; 4];
        // SAFETY: s has four entries
        unsafe { _mm256_storeu_pd(s.as_mut_ptr(), acc[p]) };
        let y = if p < 3 { b } else { d };
        let tail: f64 = cols[p][body..]
            .iter()
            .zip(&y[body..])
            .map(|(x, y)| x * y)
            .sum();
        out[p / 3][p % 3] = (s[0] + s[1]) + (s[2] + s[3]) + tail;
    }
    out
}

/// Test data: a xorshift generator of numbers uniform in `[−0.5, 0.5)` from `seed` (≠ 0).
#[cfg(test)]
pub(super) fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`dots3x2`] (AVX2 when available) against the scalar kernel (bitwise: same operations
    /// in the same order) and against plain sequential sums (independent reference, to
    /// round-off), for lengths with and without a tail after the chunks of four.
    #[test]
    fn dots3x2_is_the_scalar_kernel() {
        let mut rnd = uniform(0x9e37_79b9_7f4a_7c15);
        for n in [0, 1, 3, 4, 7, 8, 13, 340] {
            let v: Vec<Vec<f64>> = (0..8).map(|_| (0..n).map(|_| rnd()).collect()).collect();
            let a = [&v[0][..], &v[1][..], &v[2][..]];
            let c = [&v[4][..], &v[5][..], &v[6][..]];
            let [p, q] = dots3x2(a, &v[3], c, &v[7]);
            assert_eq!(p.map(f64::to_bits), dots3_body(a, &v[3]).map(f64::to_bits));
            assert_eq!(q.map(f64::to_bits), dots3_body(c, &v[7]).map(f64::to_bits));
            for (r, (x, y)) in [(p, (a, &v[3])), (q, (c, &v[7]))] {
                for k in 0..3 {
                    let plain: f64 = x[k].iter().zip(y).map(|(s, t)| s * t).sum();
                    assert!((r[k] - plain).abs() <= 1e-13 * n.max(1) as f64);
                }
            }
        }
    }
}
