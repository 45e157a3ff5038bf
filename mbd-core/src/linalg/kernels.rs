//! Small dense kernels of the contact solvers, compiled twice where it pays: for the baseline
//! x86-64 target (SSE2) and with AVX2 (+FMA), chosen at run time (`is_x86_feature_detected!`,
//! cached by std) like faer's kernels. Each output is formed by the same operations in the same
//! order in every version, so the results are bitwise the same on any x86-64 machine (the FMA
//! version of the triangular solves reproduces faer's own FMA kernels, see
//! [`lu_solve_in_place`]).

/// Column `j` of `m` as a slice (a `Mat`'s columns are contiguous; empty otherwise, which the
/// kernels' length checks then refuse). Inlined across crates: the contact kernels call it
/// once per column (on the full rolling tire 2.7 % of a step's instructions went to the call).
#[inline]
pub fn col_slice(m: &faer::Mat<f64>, j: usize) -> &[f64] {
    m.col(j)
        .try_as_col_major()
        .map_or(&[][..], |c| c.as_slice())
}

/// Whether the AVX2 versions may run on this machine.
#[cfg(target_arch = "x86_64")]
#[inline]
fn avx2() -> bool {
    std::arch::is_x86_feature_detected!("avx2")
}

/// `out += Σ_c v_c a_c` over the columns `a_c = col(c)` (each `out.len()` long) with `v_c ≠ 0`,
/// in increasing `c`: per entry the same sums in the same order as one axpy per column, but
/// up to four columns per pass over `out`.
pub fn axpy_cols<'a>(col: impl Fn(usize) -> &'a [f64], v: &[f64], out: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    {
        #[target_feature(enable = "avx2")]
        unsafe fn avx2_version<'a>(col: impl Fn(usize) -> &'a [f64], v: &[f64], out: &mut [f64]) {
            axpy_cols_body(col, v, out)
        }
        if avx2() {
            // SAFETY: AVX2 is available (checked at run time)
            return unsafe { avx2_version(col, v, out) };
        }
    }
    axpy_cols_body(col, v, out)
}

#[inline(always)]
fn axpy_cols_body<'a>(col: impl Fn(usize) -> &'a [f64], v: &[f64], out: &mut [f64]) {
    let mut cols = [0usize; 4];
    let mut k = 0;
    for (c, &vc) in v.iter().enumerate() {
        if vc != 0.0 {
            cols[k] = c;
            k += 1;
            if k == 4 {
                columns_pass(&col, v, &cols, out);
                k = 0;
            }
        }
    }
    columns_pass(&col, v, &cols[..k], out);
}

/// `out += Σ v_c a_c` over the (at most four) columns `cols` in one pass.
#[inline(always)]
fn columns_pass<'a>(col: &impl Fn(usize) -> &'a [f64], v: &[f64], cols: &[usize], out: &mut [f64]) {
    let n = out.len();
    match *cols {
        [c0] => {
            let (x0, a0) = (v[c0], &col(c0)[..n]);
            for (o, &p0) in out.iter_mut().zip(a0) {
                *o += x0 * p0;
            }
        }
        [c0, c1] => {
            let (x0, a0) = (v[c0], &col(c0)[..n]);
            let (x1, a1) = (v[c1], &col(c1)[..n]);
            for ((o, &p0), &p1) in out.iter_mut().zip(a0).zip(a1) {
                *o = *o + x0 * p0 + x1 * p1;
            }
        }
        [c0, c1, c2] => {
            let (x0, a0) = (v[c0], &col(c0)[..n]);
            let (x1, a1) = (v[c1], &col(c1)[..n]);
            let (x2, a2) = (v[c2], &col(c2)[..n]);
            for (((o, &p0), &p1), &p2) in out.iter_mut().zip(a0).zip(a1).zip(a2) {
                *o = *o + x0 * p0 + x1 * p1 + x2 * p2;
            }
        }
        [c0, c1, c2, c3] => {
            let (x0, a0) = (v[c0], &col(c0)[..n]);
            let (x1, a1) = (v[c1], &col(c1)[..n]);
            let (x2, a2) = (v[c2], &col(c2)[..n]);
            let (x3, a3) = (v[c3], &col(c3)[..n]);
            for ((((o, &p0), &p1), &p2), &p3) in out.iter_mut().zip(a0).zip(a1).zip(a2).zip(a3) {
                *o = *o + x0 * p0 + x1 * p1 + x2 * p2 + x3 * p3;
            }
        }
        _ => {}
    }
}

/// Solves `L U x = b` in place (`x` = `b` on entry) with the packed factors of faer's partial
/// pivoting LU (`L` unit lower, `U` upper; column `j` = `col(j)`, `n` rows, the permutation
/// applied by the caller), by the same algorithm as faer 0.24's
/// `solve_unit_lower_triangular_in_place` followed by `solve_upper_triangular_in_place` for
/// one right-hand side: the same recursive halving (`block_size`), the same base cases of at
/// most four rows (plain multiplies and adds), and the off-diagonal blocks applied entry by
/// entry as fused multiply-adds `x_i ← fma(a_ij, −x_j, x_i)` in faer's column order (the order
/// of faer's column-major matrix–vector kernel after its stride normalisation). Each entry of
/// the solution is thus formed by the same operations in the same order as by faer on a
/// machine with FMA (bitwise the same; checked in the tests), without faer's per-block
/// dispatch, which made the two solves of a ~60 × 60 chord step cost as much as the rest of
/// it (issue #16).
pub fn lu_solve_in_place<'a>(col: impl Fn(usize) -> &'a [f64] + Copy, n: usize, x: &mut [f64]) {
    assert!(x.len() == n && (0..n).all(|j| col(j).len() >= n));
    #[cfg(target_arch = "x86_64")]
    {
        if avx2() && std::arch::is_x86_feature_detected!("fma") {
            // SAFETY: AVX2 and FMA are available (checked at run time)
            unsafe {
                tri_fma::unit_lower_solve(col, 0, n, x);
                tri_fma::upper_solve(col, n, 0, n, x);
            }
            return;
        }
    }
    // SAFETY: no target features required
    unsafe {
        tri_base::unit_lower_solve(col, 0, n, x);
        tri_base::upper_solve(col, n, 0, n, x);
    }
}

/// faer's split of a triangular block of `n` rows (`triangular_solve::block_size`).
#[inline(always)]
fn tri_block_size(n: usize) -> usize {
    let base_rem = n / 2;
    n - if n >= 32 {
        base_rem.div_ceil(16) * 16
    } else if n >= 16 {
        base_rem.div_ceil(8) * 8
    } else if n >= 8 {
        base_rem.div_ceil(4) * 4
    } else {
        base_rem
    }
}

/// The recursive solves of [`lu_solve_in_place`], compiled once per set of target features
/// (recursive functions are not inlined into a caller with more features, so each copy
/// carries them itself: with FMA, `mul_add` is one instruction).
macro_rules! triangular_solves {
    ($module:ident $(, $feature:literal)?) => {
        mod $module {
            use super::tri_block_size;

            /// `dst_i ← fma(a_{r+i, c+k}, −vals_k, dst_i)` for `k` ascending (columns
            /// `c..c + vals.len()`, rows `r..r + dst.len()`): per entry faer's column-major
            /// matrix–vector product; rows kept in registers over the columns.
            #[inline(always)]
            fn fma_update<'a>(
                col: impl Fn(usize) -> &'a [f64] + Copy,
                c: usize,
                vals: &[f64],
                r: usize,
                dst: &mut [f64],
            ) {
                // sixteen rows at a time (four independent chains of fused multiply-adds),
                // then four, then one
                let mut wide = dst.chunks_exact_mut(16);
                let mut i = r;
                for d in &mut wide {
                    fma_rows::<16>(col, c, vals, i, d);
                    i += 16;
                }
                let mut blocks = wide.into_remainder().chunks_exact_mut(4);
                for d in &mut blocks {
                    fma_rows::<4>(col, c, vals, i, d);
                    i += 4;
                }
                for d in blocks.into_remainder().chunks_exact_mut(1) {
                    fma_rows::<1>(col, c, vals, i, d);
                    i += 1;
                }
            }

            /// `dst_l ← fma(a_{i+l, c+k}, −vals_k, dst_l)` for `k` ascending, `W` rows held
            /// in registers over the columns.
            #[inline(always)]
            fn fma_rows<'a, const W: usize>(
                col: impl Fn(usize) -> &'a [f64] + Copy,
                c: usize,
                vals: &[f64],
                i: usize,
                dst: &mut [f64],
            ) {
                let mut acc = [0.0; W];
                acc.copy_from_slice(dst);
                for (k, &v) in vals.iter().enumerate() {
                    let a = &col(c + k)[i..i + W];
                    for l in 0..W {
                        acc[l] = a[l].mul_add(-v, acc[l]);
                    }
                }
                dst.copy_from_slice(&acc);
            }

            /// Unit lower solve on rows and columns `s..s + len` (faer's
            /// `solve_unit_lower_triangular_in_place_imp`).
            $(#[target_feature(enable = $feature)])?
            pub(super) unsafe fn unit_lower_solve<'a>(
                col: impl Fn(usize) -> &'a [f64] + Copy,
                s: usize,
                len: usize,
                x: &mut [f64],
            ) {
                if len <= 4 {
                    // x_i = ((x_i + (−l_i,s) x_s) + (−l_i,s+1) x_s+1) + …
                    for i in s + 1..s + len {
                        let mut y = x[i];
                        for j in s..i {
                            y += -col(j)[i] * x[j];
                        }
                        x[i] = y;
                    }
                    return;
                }
                let bs = tri_block_size(len);
                // SAFETY: same target features as this function
                unsafe { unit_lower_solve(col, s, bs, x) };
                let (top, bot) = x.split_at_mut(s + bs);
                fma_update(col, s, &top[s..], s + bs, &mut bot[..len - bs]);
                // SAFETY: as above
                unsafe { unit_lower_solve(col, s + bs, len - bs, x) };
            }

            /// Upper solve as faer does it: the lower solve
            /// (`solve_lower_triangular_in_place_imp`) of the reversed matrix
            /// `T_pq = U_{n−1−p, n−1−q}` and right-hand side, here on its rows and columns
            /// `s..s + len`.
            $(#[target_feature(enable = $feature)])?
            pub(super) unsafe fn upper_solve<'a>(
                col: impl Fn(usize) -> &'a [f64] + Copy,
                n: usize,
                s: usize,
                len: usize,
                x: &mut [f64],
            ) {
                let t = |p: usize, q: usize| col(n - 1 - q)[n - 1 - p];
                if len <= 4 {
                    // x_p = ((x_p t_pp⁻¹ + (−t_p,s t_pp⁻¹) x_s) + …  (reciprocals, as faer)
                    for p in s..s + len {
                        let inv = 1.0 / t(p, p);
                        let mut y = x[n - 1 - p] * inv;
                        for q in s..p {
                            y += (-t(p, q) * inv) * x[n - 1 - q];
                        }
                        x[n - 1 - p] = y;
                    }
                    return;
                }
                let bs = tri_block_size(len);
                // SAFETY: same target features as this function
                unsafe { upper_solve(col, n, s, bs, x) };
                // T rows s + bs..s + len are U rows n − s − len..n − s − bs; faer's kernel
                // runs over T's columns from the last (its stride normalisation reverses
                // them): U's columns ascending
                let (head, tail) = x.split_at_mut(n - s - bs);
                fma_update(col, n - s - bs, &tail[..bs], n - s - len, &mut head[n - s - len..]);
                // SAFETY: as above
                unsafe { upper_solve(col, n, s + bs, len - bs, x) };
            }
        }
    };
}

#[cfg(target_arch = "x86_64")]
triangular_solves!(tri_fma, "avx2,fma");
triangular_solves!(tri_base);

#[cfg(test)]
mod tests {
    use super::*;

    /// Test data: a xorshift generator of numbers uniform in `[−0.5, 0.5)` from `seed` (≠ 0).
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    /// [`lu_solve_in_place`] against faer's two triangular solves on the same factors
    /// (bitwise on a machine with FMA, which faer's kernels use; else to round-off) and
    /// against the right-hand side (residual `‖A x − b‖`, independent of both), for sizes
    /// through several levels of faer's block recursion.
    #[test]
    fn lu_solve_is_faers_triangular_solves() {
        use faer::dyn_stack::{MemBuffer, MemStack};
        use faer::linalg::lu::partial_pivoting::factor::{lu_in_place, lu_in_place_scratch};
        use faer::linalg::triangular_solve::{
            solve_unit_lower_triangular_in_place, solve_upper_triangular_in_place,
        };
        use faer::{Mat, MatMut, Par};
        let mut rnd = uniform(0x2545_f491_4f6c_dd1d);
        #[cfg(target_arch = "x86_64")]
        let fma = avx2() && std::arch::is_x86_feature_detected!("fma");
        #[cfg(not(target_arch = "x86_64"))]
        let fma = false;
        for n in [
            1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 31, 32, 33, 45, 60, 63, 64, 65, 90, 97,
        ] {
            let a = Mat::from_fn(n, n, |i, j| rnd() + if i == j { 2.0 } else { 0.0 });
            let b: Vec<f64> = (0..n).map(|_| rnd()).collect();
            let mut lu = a.clone();
            let (mut perm, mut perm_inv) = (vec![0usize; n], vec![0usize; n]);
            let mut mem = MemBuffer::new(lu_in_place_scratch::<usize, f64>(
                n,
                n,
                Par::Seq,
                Default::default(),
            ));
            let _ = lu_in_place(
                lu.as_mut(),
                &mut perm,
                &mut perm_inv,
                Par::Seq,
                MemStack::new(&mut mem),
                Default::default(),
            );
            let pb: Vec<f64> = perm.iter().map(|&p| b[p]).collect();
            let mut reference = pb.clone();
            let mut r = MatMut::from_column_major_slice_mut(&mut reference, n, 1);
            solve_unit_lower_triangular_in_place(lu.as_ref(), r.as_mut(), Par::Seq);
            solve_upper_triangular_in_place(lu.as_ref(), r.as_mut(), Par::Seq);
            let mut x = pb;
            lu_solve_in_place(
                |j| lu.col(j).try_as_col_major().unwrap().as_slice(),
                n,
                &mut x,
            );
            for (i, (u, v)) in x.iter().zip(&reference).enumerate() {
                if fma {
                    assert_eq!(u.to_bits(), v.to_bits(), "n = {n}, entry {i}: {u} vs {v}");
                } else {
                    assert!(
                        (u - v).abs() <= 1e-12 * v.abs().max(1.0),
                        "n = {n}: {u} vs {v}"
                    );
                }
            }
            for i in 0..n {
                let ax: f64 = (0..n).map(|j| a[(i, j)] * x[j]).sum();
                assert!(
                    (ax - b[i]).abs() <= 1e-12,
                    "n = {n}: residual {}",
                    ax - b[i]
                );
            }
        }
    }
}
