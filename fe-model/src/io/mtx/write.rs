//! Matrix Market writer: sparse matrices in `coordinate` and dense ones in `array` format,
//! values in Rust's shortest round-trip representation (write → read reproduces every f64 bit
//! for bit).

use super::Symmetry;
use crate::FeError;
use crate::error::MatrixFileError as E;
use crate::io::err;
use crate::sparse::triplets;
use faer::MatRef;
use faer::sparse::SparseColMatRef;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

fn check_symmetric(a: SparseColMatRef<'_, usize, f64>) -> Result<(), FeError> {
    if a.nrows() != a.ncols() {
        return Err(FeError::Dimension {
            context: "Matrix Market symmetric output needs a square matrix".into(),
            expected: a.nrows(),
            got: a.ncols(),
        });
    }
    let mut map = HashMap::new();
    for (r, c, v) in triplets(a) {
        *map.entry((r, c)).or_insert(0.0) += v;
    }
    for (&(r, c), &v) in &map {
        let w = map.get(&(c, r)).copied().unwrap_or(0.0);
        if v != w {
            return Err(err(
                "<output>",
                0,
                E::NotSymmetric {
                    row: r + 1,
                    col: c + 1,
                    value: v,
                    mirror: w,
                },
            ));
        }
    }
    Ok(())
}

/// Matrix Market text of a sparse matrix in coordinate format. With
/// [`Symmetry::Symmetric`] only the lower triangle is written (the matrix must be exactly
/// symmetric).
pub fn sparse_to_string(
    a: SparseColMatRef<'_, usize, f64>, symmetry: Symmetry,
) -> Result<String, FeError> {
    if symmetry == Symmetry::Symmetric {
        check_symmetric(a)?;
    }
    let entries: Vec<_> = triplets(a)
        .filter(|&(r, c, _)| symmetry == Symmetry::General || r >= c)
        .collect();
    let mut s = String::with_capacity(entries.len() * 32 + 128);
    let sym = if symmetry == Symmetry::General {
        "general"
    } else {
        "symmetric"
    };
    let _ = writeln!(s, "%%MatrixMarket matrix coordinate real {sym}");
    let _ = writeln!(s, "% written by flowmbd fe-model");
    let _ = writeln!(s, "{} {} {}", a.nrows(), a.ncols(), entries.len());
    for (r, c, v) in entries {
        let _ = writeln!(s, "{} {} {:e}", r + 1, c + 1, v);
    }
    Ok(s)
}

/// Matrix Market text of a dense matrix in array format (symmetric: lower triangle).
pub fn dense_to_string(a: MatRef<'_, f64>, symmetry: Symmetry) -> Result<String, FeError> {
    let (m, n) = (a.nrows(), a.ncols());
    if symmetry == Symmetry::Symmetric {
        if m != n {
            return Err(FeError::Dimension {
                context: "Matrix Market symmetric output needs a square matrix".into(),
                expected: m,
                got: n,
            });
        }
        for c in 0..n {
            for r in 0..c {
                if a[(r, c)] != a[(c, r)] {
                    return Err(err(
                        "<output>",
                        0,
                        E::NotSymmetric {
                            row: r + 1,
                            col: c + 1,
                            value: a[(r, c)],
                            mirror: a[(c, r)],
                        },
                    ));
                }
            }
        }
    }
    let sym = if symmetry == Symmetry::General {
        "general"
    } else {
        "symmetric"
    };
    let mut s = String::new();
    let _ = writeln!(s, "%%MatrixMarket matrix array real {sym}");
    let _ = writeln!(s, "{m} {n}");
    for c in 0..n {
        let r0 = if symmetry == Symmetry::Symmetric {
            c
        } else {
            0
        };
        for r in r0..m {
            let _ = writeln!(s, "{:e}", a[(r, c)]);
        }
    }
    Ok(s)
}

fn write_text(path: &Path, text: &str) -> Result<(), FeError> {
    crate::io::write_atomic(path, text.as_bytes()).map_err(|source| FeError::Io {
        file: path.display().to_string(),
        source,
    })
}

/// Write a sparse matrix (coordinate format).
pub fn write_sparse(
    path: impl AsRef<Path>, a: SparseColMatRef<'_, usize, f64>, symmetry: Symmetry,
) -> Result<(), FeError> {
    write_text(path.as_ref(), &sparse_to_string(a, symmetry)?)
}

/// Write a dense matrix (array format).
pub fn write_dense(
    path: impl AsRef<Path>, a: MatRef<'_, f64>, symmetry: Symmetry,
) -> Result<(), FeError> {
    write_text(path.as_ref(), &dense_to_string(a, symmetry)?)
}
