//! Matrix Market (`.mtx`) reader and writer: `coordinate` and `array` formats, `real` /
//! `integer` fields, `general` and `symmetric` symmetry (NIST Matrix Market specification,
//! Boisvert, Pozo & Remington 1996).
//!
//! faer 0.24's `faer::io` only offers `.npy`, so this module is our own, with typed errors that
//! carry the 1-based line number ([`FeError::Matrix`]). Values are written in Rust's shortest
//! round-trip representation, so write → read reproduces every f64 bit for bit.

use super::{check_mirror, err};
use crate::FeError;
use crate::error::MatrixFileError as E;
use crate::sparse::triplets;
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Mat, MatRef};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

/// Storage format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Sparse `i j value` triplets.
    Coordinate,
    /// Dense column-major values.
    Array,
}

/// Symmetry declared in the header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Symmetry {
    /// All entries stored.
    General,
    /// Only the lower triangle stored; `a(j,i) = a(i,j)`.
    Symmetric,
}

/// A matrix read from a Matrix Market file, with explicit entries (symmetric files expanded).
#[derive(Debug, Clone, PartialEq)]
pub struct MtxMatrix {
    /// Rows.
    pub nrows: usize,
    /// Columns.
    pub ncols: usize,
    /// Format of the file.
    pub format: Format,
    /// Declared symmetry.
    pub symmetry: Symmetry,
    /// Entries `(row, col, value)`, 0-based, both triangles for symmetric files.
    pub entries: Vec<(usize, usize, f64)>,
}

impl MtxMatrix {
    /// Sparse CSC matrix (duplicate coordinates summed).
    pub fn to_sparse(&self) -> Result<SparseColMat<usize, f64>, FeError> {
        let t: Vec<_> = self
            .entries
            .iter()
            .map(|&(r, c, v)| Triplet::new(r, c, v))
            .collect();
        SparseColMat::try_new_from_triplets(self.nrows, self.ncols, &t)
            .map_err(|e| FeError::Sparse(format!("Matrix Market to sparse: {e:?}")))
    }

    /// Dense matrix (duplicates summed).
    pub fn to_dense(&self) -> Mat<f64> {
        let mut m = Mat::zeros(self.nrows, self.ncols);
        for &(r, c, v) in &self.entries {
            m[(r, c)] += v;
        }
        m
    }
}

fn parse_value(tok: &str, file: &str, line: usize) -> Result<f64, FeError> {
    let v: f64 = tok
        .parse()
        .map_err(|_| err(file, line, E::Syntax(format!("`{tok}` is not a number"))))?;
    if !v.is_finite() {
        return Err(err(file, line, E::NonFinite(tok.to_string())));
    }
    Ok(v)
}

/// Parse Matrix Market text; `file` names the source in errors.
pub fn parse(text: &str, file: &str) -> Result<MtxMatrix, FeError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let (l0, banner) = lines
        .next()
        .ok_or_else(|| err(file, 1, E::Header("empty file".into())))?;
    let b: Vec<String> = banner
        .split_whitespace()
        .map(|s| s.to_ascii_lowercase())
        .collect();
    if b.len() != 5 || b[0] != "%%matrixmarket" {
        return Err(err(
            file,
            l0,
            E::Header("expected `%%MatrixMarket matrix <format> <field> <symmetry>`".into()),
        ));
    }
    if b[1] != "matrix" {
        return Err(err(
            file,
            l0,
            E::Header(format!("unsupported object `{}`", b[1])),
        ));
    }
    let format = match b[2].as_str() {
        "coordinate" => Format::Coordinate,
        "array" => Format::Array,
        f => {
            return Err(err(
                file,
                l0,
                E::Header(format!("unsupported format `{f}`")),
            ));
        }
    };
    match b[3].as_str() {
        "real" | "integer" | "double" => {}
        f => {
            return Err(err(
                file,
                l0,
                E::Header(format!("unsupported field `{f}` (real or integer)")),
            ));
        }
    }
    let symmetry = match b[4].as_str() {
        "general" => Symmetry::General,
        "symmetric" => Symmetry::Symmetric,
        s => {
            return Err(err(
                file,
                l0,
                E::Header(format!("unsupported symmetry `{s}` (general or symmetric)")),
            ));
        }
    };
    // skip comments and blank lines to the size line
    let mut data = lines.filter(|(_, l)| {
        let t = l.trim();
        !t.is_empty() && !t.starts_with('%')
    });
    let (ls, size) = data
        .next()
        .ok_or_else(|| err(file, l0 + 1, E::Size("missing size line".into())))?;
    let dims: Vec<&str> = size.split_whitespace().collect();
    let want = if format == Format::Coordinate { 3 } else { 2 };
    if dims.len() != want {
        return Err(err(
            file,
            ls,
            E::Size(format!("expected {want} integers, found `{}`", size.trim())),
        ));
    }
    let mut d = [0usize; 3];
    for (i, t) in dims.iter().enumerate() {
        d[i] = t.parse().map_err(|_| {
            err(
                file,
                ls,
                E::Size(format!("`{t}` is not a non-negative integer")),
            )
        })?;
    }
    let (nrows, ncols) = (d[0], d[1]);
    if symmetry == Symmetry::Symmetric && nrows != ncols {
        return Err(err(
            file,
            ls,
            E::Size(format!(
                "symmetric matrix must be square, got {nrows}×{ncols}"
            )),
        ));
    }
    let mut entries = Vec::new();
    let mut last_line = ls;
    match format {
        Format::Coordinate => {
            let nnz = d[2];
            // lower-triangle key → (value, line, stored as upper?) for the symmetry check
            let mut seen: HashMap<(usize, usize), (f64, bool)> = HashMap::new();
            let mut found = 0usize;
            for (ln, l) in data {
                last_line = ln;
                if found == nnz {
                    return Err(err(file, ln, E::TooManyEntries { expected: nnz }));
                }
                let t: Vec<&str> = l.split_whitespace().collect();
                if t.len() != 3 {
                    return Err(err(
                        file,
                        ln,
                        E::Syntax(format!("expected `row col value`, found `{}`", l.trim())),
                    ));
                }
                let idx = |s: &str| -> Result<i64, FeError> {
                    s.parse::<i64>().map_err(|_| {
                        err(
                            file,
                            ln,
                            E::Syntax(format!("`{s}` is not an integer index")),
                        )
                    })
                };
                let (r, c) = (idx(t[0])?, idx(t[1])?);
                if r < 1 || c < 1 || r as usize > nrows || c as usize > ncols {
                    return Err(err(
                        file,
                        ln,
                        E::IndexOutOfRange {
                            row: r,
                            col: c,
                            nrows,
                            ncols,
                        },
                    ));
                }
                let v = parse_value(t[2], file, ln)?;
                let (r, c) = (r as usize - 1, c as usize - 1);
                found += 1;
                match symmetry {
                    Symmetry::General => entries.push((r, c, v)),
                    Symmetry::Symmetric => {
                        let upper = r < c;
                        let key = if upper { (c, r) } else { (r, c) };
                        match seen.get_mut(&key) {
                            Some((old, old_upper)) if *old_upper != upper => {
                                // both triangles given: they must agree
                                check_mirror(file, ln, (r, c), v, *old)?;
                            }
                            Some((old, _)) => *old += v, // duplicate on the same side: summed
                            None => {
                                seen.insert(key, (v, upper));
                            }
                        }
                    }
                }
            }
            if found < nnz {
                return Err(err(
                    file,
                    last_line + 1,
                    E::Truncated {
                        expected: nnz,
                        found,
                    },
                ));
            }
            if symmetry == Symmetry::Symmetric {
                let mut keys: Vec<_> = seen.into_iter().collect();
                keys.sort_by_key(|(k, _)| (k.1, k.0));
                for ((r, c), (v, _)) in keys {
                    entries.push((r, c, v));
                    if r != c {
                        entries.push((c, r, v));
                    }
                }
            }
        }
        Format::Array => {
            // column-major; symmetric: lower triangle incl. diagonal, column by column
            let positions: Vec<(usize, usize)> = match symmetry {
                Symmetry::General => (0..ncols)
                    .flat_map(|c| (0..nrows).map(move |r| (r, c)))
                    .collect(),
                Symmetry::Symmetric => (0..ncols)
                    .flat_map(|c| (c..nrows).map(move |r| (r, c)))
                    .collect(),
            };
            let mut found = 0usize;
            for (ln, l) in data {
                last_line = ln;
                for tok in l.split_whitespace() {
                    if found == positions.len() {
                        return Err(err(
                            file,
                            ln,
                            E::TooManyEntries {
                                expected: positions.len(),
                            },
                        ));
                    }
                    let v = parse_value(tok, file, ln)?;
                    let (r, c) = positions[found];
                    entries.push((r, c, v));
                    if symmetry == Symmetry::Symmetric && r != c {
                        entries.push((c, r, v));
                    }
                    found += 1;
                }
            }
            if found < positions.len() {
                return Err(err(
                    file,
                    last_line + 1,
                    E::Truncated {
                        expected: positions.len(),
                        found,
                    },
                ));
            }
        }
    }
    Ok(MtxMatrix {
        nrows,
        ncols,
        format,
        symmetry,
        entries,
    })
}

/// Read a Matrix Market file.
pub fn read(path: impl AsRef<Path>) -> Result<MtxMatrix, FeError> {
    let (name, text) = super::read_text(path.as_ref())?;
    parse(&text, &name)
}

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
    a: SparseColMatRef<'_, usize, f64>,
    symmetry: Symmetry,
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
    std::fs::write(path, text).map_err(|source| FeError::Io {
        file: path.display().to_string(),
        source,
    })
}

/// Write a sparse matrix (coordinate format).
pub fn write_sparse(
    path: impl AsRef<Path>,
    a: SparseColMatRef<'_, usize, f64>,
    symmetry: Symmetry,
) -> Result<(), FeError> {
    write_text(path.as_ref(), &sparse_to_string(a, symmetry)?)
}

/// Write a dense matrix (array format).
pub fn write_dense(
    path: impl AsRef<Path>,
    a: MatRef<'_, f64>,
    symmetry: Symmetry,
) -> Result<(), FeError> {
    write_text(path.as_ref(), &dense_to_string(a, symmetry)?)
}
