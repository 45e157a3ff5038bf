//! Spectral (FFT) mode-shape derivatives, corrected (Ribaric App. A.4, erratum E22).
//!
//! The printed (A.12)–(A.15) uses unsigned wavenumbers `0…n−1`, the factor `−2πi/n` without the
//! grid spacing, and applies a periodic transform to a non-periodic field; it gives 50–80 % error
//! (notes §1.10). Here: signed wavenumbers `k = 2π·fftfreq(N, h)`, `f' = ifft(i k fft(f))`,
//! `f'' = ifft(−k² fft(f))`, the Nyquist term dropped from odd derivatives; open grids with two
//! zero-value ends are odd-extended to period `2(b − a)` (fixed/clamped string), closed grids are
//! used as they are (belt loop, tire ring). The grid must be uniform.

use crate::error::FlowError;
use crate::grid::{End, FlowGrid, Topology};
use faer::{Mat, MatRef};
use num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// How the nodal field is extended to a periodic one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Extension {
    Periodic,
    Odd,
}

/// A planned spectral derivative on one uniform grid.
#[derive(Clone)]
pub struct SpectralOperator {
    n: usize,
    extension: Extension,
    forward: Arc<dyn Fft<f64>>,
    inverse: Arc<dyn Fft<f64>>,
    /// Signed physical wavenumbers \[rad per unit of s\], length N.
    k: Vec<f64>,
}

impl std::fmt::Debug for SpectralOperator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpectralOperator")
            .field("n", &self.n)
            .field("extension", &self.extension)
            .field("fft_len", &self.k.len())
            .finish()
    }
}

impl SpectralOperator {
    /// Number of grid nodes.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether the operator has no nodes (never true once built).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Plans the transform for `grid` (uniform to a relative 1e-9; closed, or open with two
    /// zero-value ends).
    pub fn new(grid: &FlowGrid) -> Result<Self, FlowError> {
        let n = grid.len();
        let Some(h) = grid.uniform_spacing(1e-9) else {
            return Err(FlowError::MethodNotApplicable {
                method: "spectral (FFT)",
                reason:
                    "the grid is not uniform; use finite differences or polynomial least squares"
                        .into(),
            });
        };
        let (extension, len) = match grid.topology() {
            Topology::Closed { .. } => (Extension::Periodic, n),
            Topology::Open {
                start: End::Zero(_),
                end: End::Zero(_),
            } => (Extension::Odd, 2 * (n + 1)),
            Topology::Open { .. } => {
                return Err(FlowError::MethodNotApplicable {
                    method: "spectral (FFT)",
                    reason: "an open grid needs zero-value (fixed) ends for the odd extension"
                        .into(),
                });
            }
        };
        let mut planner = FftPlanner::<f64>::new();
        let forward = planner.plan_fft_forward(len);
        let inverse = planner.plan_fft_inverse(len);
        let base = 2.0 * std::f64::consts::PI / (len as f64 * h);
        let k = (0..len)
            .map(|m| {
                let signed = if 2 * m < len {
                    m as f64
                } else {
                    m as f64 - len as f64
                };
                signed * base
            })
            .collect();
        Ok(Self {
            n,
            extension,
            forward,
            inverse,
            k,
        })
    }

    /// First and second derivatives of every column of `values` (`n × m`).
    pub fn apply(&self, values: MatRef<'_, f64>) -> (Mat<f64>, Mat<f64>) {
        let n = self.n;
        let len = self.k.len();
        let mut d1 = Mat::<f64>::zeros(n, values.ncols());
        let mut d2 = Mat::<f64>::zeros(n, values.ncols());
        let mut buf = vec![Complex::new(0.0, 0.0); len];
        let mut b1 = vec![Complex::new(0.0, 0.0); len];
        let nyquist = len.is_multiple_of(2).then_some(len / 2);
        for c in 0..values.ncols() {
            buf.iter_mut().for_each(|z| *z = Complex::new(0.0, 0.0));
            match self.extension {
                Extension::Periodic => {
                    for j in 0..n {
                        buf[j].re = values[(j, c)];
                    }
                }
                Extension::Odd => {
                    for j in 0..n {
                        buf[j + 1].re = values[(j, c)];
                        buf[len - 1 - j].re = -values[(j, c)];
                    }
                }
            }
            self.forward.process(&mut buf);
            for m in 0..len {
                let k = self.k[m];
                b1[m] = if Some(m) == nyquist {
                    Complex::new(0.0, 0.0)
                } else {
                    buf[m] * Complex::new(0.0, k)
                };
                buf[m] *= -k * k;
            }
            self.inverse.process(&mut b1);
            self.inverse.process(&mut buf);
            let off = if self.extension == Extension::Odd {
                1
            } else {
                0
            };
            let scale = 1.0 / len as f64;
            for j in 0..n {
                d1[(j, c)] = b1[j + off].re * scale;
                d2[(j, c)] = buf[j + off].re * scale;
            }
        }
        (d1, d2)
    }
}

/// The literal, uncorrected (A.12)–(A.15): unsigned indices `0…n−1`, factor `−2πi/n`, no spacing,
/// plain periodic transform of the nodal values. Kept only to document erratum E22 (tests show
/// its error); do not use it for models.
pub fn literal_a13(values: MatRef<'_, f64>) -> (Mat<f64>, Mat<f64>) {
    let n = values.nrows();
    let mut planner = FftPlanner::<f64>::new();
    let fwd = planner.plan_fft_forward(n);
    let inv = planner.plan_fft_inverse(n);
    let mut d1 = Mat::<f64>::zeros(n, values.ncols());
    let mut d2 = Mat::<f64>::zeros(n, values.ncols());
    for c in 0..values.ncols() {
        let mut buf: Vec<Complex<f64>> =
            (0..n).map(|j| Complex::new(values[(j, c)], 0.0)).collect();
        fwd.process(&mut buf);
        let f = Complex::new(0.0, -2.0 * std::f64::consts::PI / n as f64);
        let mut b1: Vec<Complex<f64>> = buf
            .iter()
            .enumerate()
            .map(|(m, z)| f * m as f64 * z)
            .collect();
        let mut b2: Vec<Complex<f64>> = buf
            .iter()
            .enumerate()
            .map(|(m, z)| f * f * (m * m) as f64 * z)
            .collect();
        inv.process(&mut b1);
        inv.process(&mut b2);
        for j in 0..n {
            d1[(j, c)] = b1[j].re / n as f64;
            d2[(j, c)] = b2[j].re / n as f64;
        }
    }
    (d1, d2)
}
