//! Runtime instruction-set dispatch for the hot element and matrix kernels.
//!
//! The workspace is compiled for the baseline x86-64 instruction set (SSE2, two doubles per
//! vector), so that its binaries run on any x86-64 machine. [`dispatch`] runs a [`Kernel`]
//! compiled a second time for AVX2 + FMA (four doubles per vector) when the machine has them,
//! through the runtime detection of `pulp` (the SIMD layer faer itself dispatches with). Rust
//! never contracts `a * b + c` into a fused multiply–add on its own, and the loops it
//! vectorises are element-wise (a reduction is not reordered), so a dispatched kernel gives the
//! same bits as the baseline one: only its speed differs.

/// A kernel for [`dispatch`]: its [`Kernel::run`], and everything `run` calls that should be
/// compiled for the wider instruction set, must be `#[inline(always)]` (a function that is not
/// inlined keeps the baseline code).
pub trait Kernel {
    /// What the kernel returns.
    type Output;
    /// The kernel's work.
    fn run(self) -> Self::Output;
}

/// `pulp`'s operation around a [`Kernel`].
struct Op<K>(K);

impl<K: Kernel> pulp::WithSimd for Op<K> {
    type Output = K::Output;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> K::Output {
        self.0.run()
    }
}

/// Runs `kernel` compiled for the best instruction set of this machine (AVX2 + FMA where
/// available, the baseline otherwise).
#[inline]
pub fn dispatch<K: Kernel>(kernel: K) -> K::Output {
    pulp::Arch::new().dispatch(Op(kernel))
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Mix<'a> {
        x: &'a [f64],
        y: &'a [f64],
        out: &'a mut [f64],
    }

    impl Kernel for Mix<'_> {
        type Output = ();
        #[inline(always)]
        fn run(self) {
            for ((o, a), b) in self.out.iter_mut().zip(self.x).zip(self.y) {
                *o = a * 1.7 - b / 3.0 + (a * a + b * b).sqrt();
            }
        }
    }

    // Reference: the same element-wise kernel run without dispatch, bit for bit.
    #[test]
    fn dispatched_kernel_gives_the_baseline_bits() {
        let x: Vec<f64> = (0..1001).map(|i| (i as f64 * 0.37).sin()).collect();
        let y: Vec<f64> = (0..1001).map(|i| (i as f64 * 0.11).cos()).collect();
        let mut base = vec![0.0; x.len()];
        Mix {
            x: &x,
            y: &y,
            out: &mut base,
        }
        .run();
        let mut fast = vec![0.0; x.len()];
        dispatch(Mix {
            x: &x,
            y: &y,
            out: &mut fast,
        });
        assert!(
            base.iter()
                .zip(&fast)
                .all(|(a, b)| a.to_bits() == b.to_bits())
        );
    }
}
