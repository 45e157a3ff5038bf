//! The row-major dense matrix–vector product `y = A x` (rows of `A` contiguous, e.g. the
//! transpose of a stored column-major matrix) several rows at a time, bitwise equal to faer's
//! `matvec_rowmajor` kernel (faer 0.24, pulp's AVX2+FMA `V3` instruction set; faer is built
//! here without pulp's `x86-v4` feature, so `V3` is the widest it uses).
//!
//! faer forms each output entry as one dot product of a row with `x` (its
//! `inner_prod_no_conj_simd`): with `k` the row length, `⌊k/4⌋` full vectors of four `f64`
//! (no alignment head: faer's `SimdCtx::new` has offset 0) and a tail of the last `k mod 4`
//! entries read with a masked load (zeros in the other lanes); four vector accumulators, the
//! full vectors in batches of four consecutive vectors, vector `q` of a batch fused-multiply-
//! added (`vfmadd`, `l·r + acc` rounded once) into accumulator `q`; the `r = ⌊k/4⌋ mod 4`
//! vectors after the last batch into accumulators `0..r`, then the tail into accumulator `r`;
//! the reduction `((a₀ + a₁) + (a₂ + a₃))`, then the upper half of the 256-bit sum added to
//! the lower half, then lane 0 plus lane 1. This module does exactly these operations in this
//! order for each row, but for [`ROWS`] rows per pass, so that each load of `x` serves
//! several rows and `4·ROWS` independent fused multiply–add chains are in flight (faer has
//! four, one row at a time, and is bound by their latency and by the loads of `x`). The same
//! instructions in the same order give the same bits: tested against faer over many shapes
//! in `linalg::tests`.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64::{
    __m256d, _mm_add_pd, _mm_cvtsd_f64, _mm_unpackhi_pd, _mm256_add_pd, _mm256_castpd256_pd128,
    _mm256_extractf128_pd, _mm256_fmadd_pd, _mm256_loadu_pd, _mm256_maskload_pd,
    _mm256_setr_epi64x, _mm256_setzero_pd,
};

/// Rows per pass of the kernel: `4·ROWS` vector accumulators (12 of the 16 AVX2 registers for
/// 3 rows, leaving registers for `x` and the loads).
pub(super) const ROWS: usize = 3;

/// Whether this machine runs faer's `V3` kernels (pulp's `V3::try_new`: the same features),
/// i.e. whether [`matvec_rows`] reproduces faer's results here.
#[cfg(target_arch = "x86_64")]
pub(super) fn available() -> bool {
    use std::arch::is_x86_feature_detected as has;
    has!("sse")
        && has!("sse2")
        && has!("fxsr")
        && has!("sse3")
        && has!("ssse3")
        && has!("sse4.1")
        && has!("sse4.2")
        && has!("popcnt")
        && has!("avx")
        && has!("avx2")
        && has!("bmi1")
        && has!("bmi2")
        && has!("fma")
        && has!("lzcnt")
}

/// `out[i] = Σ_j a[i·rs + j] x[j]` for `i < out.len()`, `j < x.len()` (module documentation
/// for the reduction order).
///
/// # Safety
/// AVX2 and FMA are available ([`available`]); `a` points to `out.len()` rows of `x.len()`
/// readable `f64` each, row `i` starting at `a + i·rs`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
pub(super) unsafe fn matvec_rows(a: *const f64, rs: usize, x: &[f64], out: &mut [f64]) {
    let k = x.len();
    let m = out.len();
    let mut i = 0;
    while i + ROWS <= m {
        // SAFETY: rows i..i+ROWS exist (caller's contract)
        let mut rows = [a; ROWS];
        for (r, p) in rows.iter_mut().enumerate() {
            *p = unsafe { a.add((i + r) * rs) };
        }
        // SAFETY: as above, AVX2 and FMA available
        let dots = unsafe { dot_rows::<ROWS>(rows, x.as_ptr(), k) };
        out[i..i + ROWS].copy_from_slice(&dots);
        i += ROWS;
    }
    while i < m {
        // SAFETY: row i exists
        let dots = unsafe { dot_rows::<1>([a.add(i * rs)], x.as_ptr(), k) };
        out[i] = dots[0];
        i += 1;
    }
}

/// The dot products of `R` rows (each `k` long) with `x` (`k` long), each in faer's order.
#[cfg(target_arch = "x86_64")]
#[inline]
#[target_feature(enable = "avx2,fma")]
unsafe fn dot_rows<const R: usize>(rows: [*const f64; R], x: *const f64, k: usize) -> [f64; R] {
    let nv = k / 4;
    let nb = nv / 4;
    let rem = nv % 4;
    let tail = k % 4;
    let z = _mm256_setzero_pd();
    let mut acc: [[__m256d; 4]; R] = [[z; 4]; R];
    // SAFETY (all loads): offsets below 4·nv ≤ k on rows and x of length k; the tail's masked
    // load reads only lanes below k
    unsafe {
        for b in 0..nb {
            let base = 16 * b;
            for q in 0..4 {
                let xv = _mm256_loadu_pd(x.add(base + 4 * q));
                for r in 0..R {
                    let av = _mm256_loadu_pd(rows[r].add(base + 4 * q));
                    acc[r][q] = _mm256_fmadd_pd(av, xv, acc[r][q]);
                }
            }
        }
        let base = 16 * nb;
        for q in 0..rem {
            let xv = _mm256_loadu_pd(x.add(base + 4 * q));
            for r in 0..R {
                let av = _mm256_loadu_pd(rows[r].add(base + 4 * q));
                acc[r][q] = _mm256_fmadd_pd(av, xv, acc[r][q]);
            }
        }
        if tail > 0 {
            let t = tail as i64;
            let lane = |l: i64| if l < t { -1 } else { 0 };
            let mask = _mm256_setr_epi64x(lane(0), lane(1), lane(2), lane(3));
            let xv = _mm256_maskload_pd(x.add(4 * nv), mask);
            for r in 0..R {
                let av = _mm256_maskload_pd(rows[r].add(4 * nv), mask);
                acc[r][rem] = _mm256_fmadd_pd(av, xv, acc[r][rem]);
            }
        }
    }
    let mut out = [0.0; R];
    for r in 0..R {
        let [a0, a1, a2, a3] = acc[r];
        let s = _mm256_add_pd(_mm256_add_pd(a0, a1), _mm256_add_pd(a2, a3));
        let h = _mm_add_pd(_mm256_castpd256_pd128(s), _mm256_extractf128_pd::<1>(s));
        // lane 0 + lane 1 (pulp: `_mm_add_sd(h, movehl(h))`, the same rounded sum)
        out[r] = _mm_cvtsd_f64(h) + _mm_cvtsd_f64(_mm_unpackhi_pd(h, h));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::{matvec, matvec_faer};
    use faer::Mat;

    /// Pseudo-random values over several decades and both signs (a fixed LCG), so that the
    /// rounding of every sum depends on the reduction order.
    fn values(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                let u = (s >> 11) as f64 / (1u64 << 53) as f64;
                let e = ((s >> 3) % 7) as i32 - 3;
                (u - 0.5) * 10f64.powi(e)
            })
            .collect()
    }

    /// The kernel equals faer's row-major matrix–vector product bit for bit (faer's own
    /// kernel is the reference: module documentation), for every row length `k` around the
    /// vector widths (`k mod 16` all values, tails 0–3), row counts around [`super::ROWS`],
    /// the tire's shapes (682×341, 341×341, 337×336), starts of rows and `x` not aligned to
    /// 32 bytes, and an odd row stride; and it equals the plain dot products to round-off
    /// (an independent check that it is the product at all).
    #[test]
    fn rowmajor_kernel_equals_faer_bitwise() {
        let mut shapes: Vec<(usize, usize)> = Vec::new();
        for m in [1, 2, 3, 4, 5, 7] {
            for k in 1..=40 {
                shapes.push((m, k));
            }
        }
        shapes.extend([
            (1, 1),
            (13, 63),
            (64, 64),
            (65, 67),
            (100, 101),
            (341, 341),
            (341, 682),
            (336, 337),
            (350, 700),
            (700, 350),
        ]);
        let mut checked_fast = false;
        for &(m, k) in &shapes {
            for (off, xoff, pad) in [(0, 0, 0), (1, 3, 0), (3, 1, 5)] {
                // stored b: (off + k + pad) × m, column-major; a = rows off..off+k of b,
                // transposed: m × k with contiguous rows starting off entries into each column
                let b = Mat::<f64>::from_fn(off + k + pad, m, |i, j| {
                    values(1, (i * 7919 + j * 104_729) as u64)[0]
                });
                let a = b.as_ref().subrows(off, k).transpose();
                assert_eq!(a.col_stride(), 1);
                let xs = values(xoff + k, (m * 31 + k) as u64);
                let x = &xs[xoff..];
                let mut fast = vec![f64::NAN; m];
                let mut reference = vec![f64::NAN; m];
                matvec(a, x, &mut fast);
                matvec_faer(a, x, &mut reference);
                for i in 0..m {
                    assert_eq!(
                        fast[i].to_bits(),
                        reference[i].to_bits(),
                        "{m}x{k} (offsets {off}, {xoff}, pad {pad}) row {i}: {} vs {}",
                        fast[i],
                        reference[i]
                    );
                    let plain: f64 = (0..k).map(|j| a[(i, j)] * x[j]).sum();
                    let scale: f64 = (0..k).map(|j| (a[(i, j)] * x[j]).abs()).sum();
                    assert!((fast[i] - plain).abs() <= 1e-14 * scale.max(f64::MIN_POSITIVE));
                }
                checked_fast |= a.row_stride() > 1;
            }
        }
        assert!(checked_fast);
        #[cfg(target_arch = "x86_64")]
        eprintln!("AVX2+FMA kernel used: {}", super::available());
    }

    /// A column-major matrix (not the kernel's layout) still gives faer's result.
    #[test]
    fn column_major_falls_back_to_faer() {
        let a = Mat::<f64>::from_fn(37, 23, |i, j| values(1, (i * 23 + j) as u64)[0]);
        let x = values(23, 5);
        let mut y = vec![0.0; 37];
        let mut r = vec![1.0; 37];
        matvec(a.as_ref(), &x, &mut y);
        matvec_faer(a.as_ref(), &x, &mut r);
        assert_eq!(y, r);
    }
}
