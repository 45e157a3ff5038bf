//! Matrix Market (`.mtx`) reader and writer: `coordinate` and `array` formats, `real` /
//! `integer` fields, `general` and `symmetric` symmetry (NIST Matrix Market specification,
//! Boisvert, Pozo & Remington 1996).
//!
//! faer 0.24's `faer::io` only offers `.npy`, so this module is our own, with typed errors that
//! carry the 1-based line number ([`FeError::Matrix`]). Values are written in Rust's shortest
//! round-trip representation, so write → read reproduces every f64 bit for bit.
//!
//! # Sizes from the file are never trusted
//!
//! Nothing is allocated from the counts of the size line: entries are stored as they are read,
//! so memory follows the file's length, and the declared counts are compared with what was
//! read (a short file is [`MatrixFileError::Truncated`](crate::error::MatrixFileError), a long
//! one `TooManyEntries`). The one allocation a header does drive, the `ncols + 1` column
//! pointers of a sparse matrix (and the `nrows` of its row work arrays), is bounded by
//! [`ReadOptions::max_dim`] ([`DEFAULT_MAX_DIM`] rows or columns unless raised, as the apps'
//! `--allow-large` does); a larger size line is refused with
//! [`MatrixFileError::TooLarge`](crate::error::MatrixFileError) before anything is allocated.
//!
//! # Matrices that must be symmetric
//!
//! A stiffness or mass matrix read with [`ReadOptions::symmetric`] must be square and
//! symmetric. A file whose header says `general` but which stores only one triangle (a common
//! export slip: the other triangle would silently be read as zero and the eigenvalues would be
//! those of a triangular matrix) is **refused**, not repaired, with
//! [`MatrixFileError::OneTriangle`](crate::error::MatrixFileError) at line 1: the reader
//! cannot tell a slip from a deliberately triangular matrix, and the fix (`symmetric` in the
//! header) is one word. A `general` file with both triangles must agree with its transpose to
//! [`SYMMETRY_RTOL`] (`NotSymmetric` names the entry and its line).
//!
//! Large coordinate files are parsed in parallel (rayon) in newline-aligned chunks; the
//! result, including the first error and its line, is the same as a sequential read.

mod header;
mod scan;
mod symmetry;
mod write;

pub use write::{dense_to_string, sparse_to_string, write_dense, write_sparse};

use crate::FeError;
use faer::Mat;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use std::path::Path;

/// Default ceiling on the rows and columns of a matrix read from a file: 10⁷ (the column
/// pointers of a sparse matrix of that size take 80 MB). Raise it with [`ReadOptions::max_dim`].
pub const DEFAULT_MAX_DIM: usize = 10_000_000;

/// Relative tolerance of the symmetry check of `general` files read with
/// [`ReadOptions::symmetric`]: `|a_ij − a_ji| ≤ 10⁻⁸·max(|a_ij|, |a_ji|) + 10⁻¹⁴·max|A|`.
pub const SYMMETRY_RTOL: f64 = 1e-8;

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

/// How a file is read: the size ceiling and whether the matrix must be symmetric.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReadOptions {
    /// Largest accepted number of rows or columns (default [`DEFAULT_MAX_DIM`]); values
    /// beyond what a sparse matrix can index (`isize::MAX / 16`) are refused whatever this is.
    pub max_dim: usize,
    /// The matrix must be square and symmetric (a stiffness or mass matrix): `general` files
    /// storing one triangle are refused, others are checked to [`SYMMETRY_RTOL`].
    pub require_symmetric: bool,
}

impl Default for ReadOptions {
    fn default() -> Self {
        Self {
            max_dim: DEFAULT_MAX_DIM,
            require_symmetric: false,
        }
    }
}

impl ReadOptions {
    /// Options for a stiffness or mass matrix: square and symmetric, default ceiling.
    pub fn symmetric() -> Self {
        Self {
            require_symmetric: true,
            ..Self::default()
        }
    }

    /// Lift the size ceiling when `yes` (the apps' `--allow-large`).
    pub fn allow_large(mut self, yes: bool) -> Self {
        if yes {
            self.max_dim = usize::MAX;
        }
        self
    }
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
    /// Sparse CSC matrix (duplicate coordinates summed, in file order). Built directly by a
    /// counting sort over the columns and a per-column sort of the rows, O(nnz + n).
    pub fn to_sparse(&self) -> Result<SparseColMat<usize, f64>, FeError> {
        let (m, n) = (self.nrows, self.ncols);
        let mut col_ptr = vec![0usize; n + 1];
        for &(r, c, _) in &self.entries {
            if r >= m || c >= n {
                return Err(FeError::Index {
                    context: format!("Matrix Market entry ({}, {})", r + 1, c + 1),
                    index: r.max(c),
                    size: m.min(n),
                });
            }
            col_ptr[c + 1] += 1;
        }
        for j in 0..n {
            col_ptr[j + 1] += col_ptr[j];
        }
        // counting sort straight into the row and value arrays (file order within a column)
        let nnz = col_ptr[n];
        let mut next = col_ptr.clone();
        let mut rows = vec![0usize; nnz];
        let mut vals = vec![0.0f64; nnz];
        for &(r, c, v) in &self.entries {
            rows[next[c]] = r;
            vals[next[c]] = v;
            next[c] += 1;
        }
        drop(next);
        // rows ascending within each column (stable: duplicates keep file order), then
        // duplicates summed in place
        let mut scratch: Vec<(usize, f64)> = Vec::new();
        let mut ptr = vec![0usize; n + 1];
        let mut w = 0usize;
        for j in 0..n {
            let (a, b) = (col_ptr[j], col_ptr[j + 1]);
            if !rows[a..b].is_sorted() {
                scratch.clear();
                scratch.extend(rows[a..b].iter().copied().zip(vals[a..b].iter().copied()));
                scratch.sort_by_key(|p| p.0);
                for (k, &(r, v)) in scratch.iter().enumerate() {
                    rows[a + k] = r;
                    vals[a + k] = v;
                }
            }
            for q in a..b {
                if w > ptr[j] && rows[w - 1] == rows[q] {
                    vals[w - 1] += vals[q];
                } else {
                    rows[w] = rows[q];
                    vals[w] = vals[q];
                    w += 1;
                }
            }
            ptr[j + 1] = w;
        }
        rows.truncate(w);
        vals.truncate(w);
        let symbolic = SymbolicSparseColMat::new_checked(m, n, ptr, None, rows);
        Ok(SparseColMat::new(symbolic, vals))
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

/// Parse Matrix Market text with the default [`ReadOptions`]; `file` names the source in
/// errors.
pub fn parse(text: &str, file: &str) -> Result<MtxMatrix, FeError> {
    parse_with(text.as_bytes(), file, &ReadOptions::default())
}

/// Parse Matrix Market bytes; `file` names the source in errors. Never panics and never
/// allocates from the header's counts (module documentation).
pub fn parse_with(data: &[u8], file: &str, opts: &ReadOptions) -> Result<MtxMatrix, FeError> {
    let h = header::parse(data, file, opts.max_dim)?;
    let body = &data[h.data_offset..];
    let entries = match h.format {
        Format::Coordinate => {
            let (entries, any_upper) = scan::coordinate(
                body,
                h.data_line,
                h.size_line,
                h.nrows,
                h.ncols,
                h.nnz,
                file,
                h.symmetry == Symmetry::Symmetric,
            )?;
            match h.symmetry {
                Symmetry::General => entries,
                Symmetry::Symmetric => {
                    symmetry::expand(entries, any_upper, body, h.data_line, file)?
                }
            }
        }
        Format::Array => scan::array(body, h.data_line, h.size_line, &h, file)?,
    };
    if opts.require_symmetric {
        symmetry::require(&entries, &h, body, file)?;
    }
    Ok(MtxMatrix {
        nrows: h.nrows,
        ncols: h.ncols,
        format: h.format,
        symmetry: h.symmetry,
        entries,
    })
}

/// Read a Matrix Market file with the default [`ReadOptions`].
pub fn read(path: impl AsRef<Path>) -> Result<MtxMatrix, FeError> {
    read_with(path, &ReadOptions::default())
}

/// Read a Matrix Market file with `opts` (a directory or unreadable path is a
/// [`FeError::Io`] naming it).
pub fn read_with(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<MtxMatrix, FeError> {
    let (name, data) = super::read_bytes(path.as_ref())?;
    parse_with(&data, &name, opts)
}
