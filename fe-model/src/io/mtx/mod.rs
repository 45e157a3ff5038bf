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
use rayon::prelude::*;
use scan::Slot;
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
    /// counting sort over the columns and a per-column merge or sort of the rows, O(nnz + n);
    /// large matrices are filled in parallel, one range of columns per thread (each thread
    /// scans all entries and keeps its columns', so the result is that of a sequential fill).
    pub fn to_sparse(&self) -> Result<SparseColMat<usize, f64>, FeError> {
        let (m, n) = (self.nrows, self.ncols);
        let mut col_ptr = vec![0usize; n + 1];
        // whether the entries are all those on or below the diagonal, then all those above (a
        // symmetric file's lower triangle and its mirrors), and where the second part starts
        let (mut upper_from, mut partitioned) = (None, true);
        for (k, &(r, c, _)) in self.entries.iter().enumerate() {
            if r < c {
                upper_from.get_or_insert(k);
            } else if upper_from.is_some() {
                partitioned = false;
            }
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
        // Filling the upper part first gives each column its rows above the diagonal, then
        // those below: already ascending when the file lists its lower triangle column by
        // column, so no sort. Entries at one position all lie in one part, so their order,
        // and the order of their sum, is the file's either way.
        let e = self.entries.as_slice();
        let parts = match upper_from {
            Some(h) if partitioned => [Part::direct(&e[h..]), Part::direct(&e[..h])],
            _ => [Part::direct(e), Part::direct(&[])],
        };
        Ok(csc_from_parts(m, n, col_ptr, &parts))
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

/// Entries fed to the CSC build: as stored, or mirrored (`(r, c, v)` placed at `(c, r)`,
/// diagonal entries skipped: the upper triangle of a symmetric file's lower triangle).
#[derive(Clone, Copy)]
struct Part<'a, T> {
    entries: &'a [T],
    mirror: bool,
}

impl<'a, T> Part<'a, T> {
    fn direct(entries: &'a [T]) -> Self {
        Self {
            entries,
            mirror: false,
        }
    }
}

/// The position `(row, col)` and value at which an entry of `part` lands, if any.
#[inline(always)]
fn placed<T: Slot>(part: Part<'_, T>, e: T) -> Option<(usize, usize, f64)> {
    let (r, c, v) = e.get();
    if !part.mirror {
        Some((r, c, v))
    } else if r != c {
        Some((c, r, v))
    } else {
        None
    }
}

/// The `m × n` CSC matrix of the entries of `parts` (all in range), duplicates summed in
/// order: `col_ptr` holds the column starts of all entries placed (`n + 1`, prefix sums). The
/// columns' rows are scattered in part order, then put in ascending order (a stable merge of
/// two ascending runs, or a stable sort) and duplicates summed. Large matrices are filled in
/// parallel, one range of columns per thread (each thread scans all entries and keeps its
/// columns', so the result is that of a sequential fill).
fn csc_from_parts<T: Slot>(
    m: usize, n: usize, col_ptr: Vec<usize>, parts: &[Part<'_, T>],
) -> SparseColMat<usize, f64> {
    let nnz = col_ptr[n];
    let mut rows = vec![0usize; nnz];
    let mut vals = vec![0.0f64; nnz];
    // distinct rows per column after summing duplicates, at the front of its block
    let mut kept = vec![0usize; n];
    // column ranges with about the same number of entries, one per thread
    let parts_n = if nnz >= 1 << 20 {
        rayon::current_num_threads().clamp(1, 16)
    } else {
        1
    };
    let mut cuts = vec![0usize];
    for t in 1..parts_n {
        let j = col_ptr.partition_point(|&p| p < nnz * t / parts_n).min(n);
        cuts.push(j.max(cuts[t - 1]));
    }
    cuts.push(n);
    let mut tasks = Vec::with_capacity(parts_n);
    let (mut rr, mut vr, mut kr) = (
        rows.as_mut_slice(),
        vals.as_mut_slice(),
        kept.as_mut_slice(),
    );
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let len = col_ptr[hi] - col_ptr[lo];
        let (r0, r1) = rr.split_at_mut(len);
        let (v0, v1) = vr.split_at_mut(len);
        let (k0, k1) = kr.split_at_mut(hi - lo);
        tasks.push((lo, hi, r0, v0, k0));
        (rr, vr, kr) = (r1, v1, k1);
    }
    tasks.into_par_iter().for_each(|(lo, hi, r, v, k)| {
        fill_columns(parts, &col_ptr, lo..hi, r, v, k);
    });
    // close up the columns (moves only where duplicates were summed)
    let mut ptr = col_ptr;
    let mut w = 0usize;
    for j in 0..n {
        let (a, k) = (ptr[j], kept[j]);
        if a != w {
            rows.copy_within(a..a + k, w);
            vals.copy_within(a..a + k, w);
        }
        ptr[j] = w;
        w += k;
    }
    ptr[n] = w;
    rows.truncate(w);
    vals.truncate(w);
    let symbolic = SymbolicSparseColMat::new_checked(m, n, ptr, None, rows);
    SparseColMat::new(symbolic, vals)
}

/// Fill the columns `cols` of a CSC matrix from the entries of `parts` (all in range): `rows`,
/// `vals` are the columns' blocks (`col_ptr[cols.start]..col_ptr[cols.end]`), filled in entry
/// order, then each column's rows put in ascending order (stable: duplicates keep entry order)
/// and duplicates summed at the front of the block, their number in `kept`.
fn fill_columns<T: Slot>(
    parts: &[Part<'_, T>], col_ptr: &[usize], cols: std::ops::Range<usize>, rows: &mut [usize],
    vals: &mut [f64], kept: &mut [usize],
) {
    let base = col_ptr[cols.start];
    let mut next: Vec<usize> = col_ptr[cols.clone()].iter().map(|p| p - base).collect();
    for &part in parts {
        for &e in part.entries {
            if let Some((r, c, v)) = placed(part, e)
                && cols.contains(&c)
            {
                let q = &mut next[c - cols.start];
                rows[*q] = r;
                vals[*q] = v;
                *q += 1;
            }
        }
    }
    drop(next);
    let mut scratch: Vec<(usize, f64)> = Vec::new();
    for j in cols.clone() {
        let (a, b) = (col_ptr[j] - base, col_ptr[j + 1] - base);
        if let Some(d) = rows[a..b].windows(2).position(|w| w[0] > w[1]) {
            if rows[a + d + 1..b].is_sorted() {
                // two ascending runs (a symmetric file's column: its lower entries, then the
                // mirrors): a stable merge, the same order as the stable sort below
                merge_runs(&mut rows[a..b], &mut vals[a..b], d + 1, &mut scratch);
            } else {
                scratch.clear();
                scratch.extend(rows[a..b].iter().copied().zip(vals[a..b].iter().copied()));
                scratch.sort_by_key(|p| p.0);
                for (k, &(r, v)) in scratch.iter().enumerate() {
                    rows[a + k] = r;
                    vals[a + k] = v;
                }
            }
        }
        let mut w = a;
        for q in a..b {
            if w > a && rows[w - 1] == rows[q] {
                vals[w - 1] += vals[q];
            } else {
                rows[w] = rows[q];
                vals[w] = vals[q];
                w += 1;
            }
        }
        kept[j - cols.start] = w - a;
    }
}

/// Stable merge of the ascending runs `rows[..mid]` and `rows[mid..]` (with their `vals`):
/// on equal rows the first run's entry comes first.
fn merge_runs(rows: &mut [usize], vals: &mut [f64], mid: usize, scratch: &mut Vec<(usize, f64)>) {
    scratch.clear();
    scratch.extend(rows[..mid].iter().copied().zip(vals[..mid].iter().copied()));
    let (mut i, mut k, mut w) = (0usize, mid, 0usize);
    while i < scratch.len() {
        if k < rows.len() && rows[k] < scratch[i].0 {
            rows[w] = rows[k];
            vals[w] = vals[k];
            k += 1;
        } else {
            (rows[w], vals[w]) = scratch[i];
            i += 1;
        }
        w += 1;
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
    match h.format {
        Format::Coordinate => {
            let mirror_room = h.symmetry == Symmetry::Symmetric;
            let (entries, any_upper) = coordinate_entries(body, &h, file, mirror_room)?;
            finish(entries, any_upper, &h, body, file, opts)
        }
        Format::Array => {
            let entries = scan::array(body, h.data_line, h.size_line, &h, file)?;
            finish(entries, false, &h, body, file, opts)
        }
    }
}

/// The triplets of a coordinate file's data `body` ([`scan::coordinate`]).
fn coordinate_entries<T: Slot>(
    body: &[u8], h: &header::Header, file: &str, mirror_room: bool,
) -> Result<(Vec<T>, bool), FeError> {
    scan::coordinate(
        body,
        h.data_line,
        h.size_line,
        h.nrows,
        h.ncols,
        h.nnz,
        file,
        mirror_room,
    )
}

/// The matrix of parsed `entries`: a coordinate `symmetric` file's mirrored (arrays come
/// mirrored from the scanner), then checked when `opts` require symmetry.
fn finish(
    entries: scan::Entries, any_upper: bool, h: &header::Header, body: &[u8], file: &str,
    opts: &ReadOptions,
) -> Result<MtxMatrix, FeError> {
    let entries = match (h.format, h.symmetry) {
        (Format::Coordinate, Symmetry::Symmetric) => {
            symmetry::expand(entries, any_upper, body, h.data_line, file)?
        }
        _ => entries,
    };
    if opts.require_symmetric {
        symmetry::require(&entries, h, body, file)?;
    }
    Ok(MtxMatrix {
        nrows: h.nrows,
        ncols: h.ncols,
        format: h.format,
        symmetry: h.symmetry,
        entries,
    })
}

/// Parse Matrix Market bytes straight into a CSC matrix: the same matrix, bit for bit, and the
/// same errors as [`parse_with`] followed by [`MtxMatrix::to_sparse`], without the expanded
/// entries. A coordinate file (the usual sparse export) is scanned into compact
/// `(u32, u32, f64)` entries (16 bytes, not 24) and a `symmetric` one's lower triangle is
/// mirrored while filling the columns, not stored twice; other files (arrays, an upper
/// triangle in a `symmetric` file, a `general` one that must be symmetric, more than
/// `u32::MAX` rows or columns) take the general path.
pub fn parse_sparse_with(
    data: &[u8], file: &str, opts: &ReadOptions,
) -> Result<SparseColMat<usize, f64>, FeError> {
    let h = header::parse(data, file, opts.max_dim)?;
    let fits = |d: usize| u32::try_from(d).is_ok();
    if h.format != Format::Coordinate || !fits(h.nrows) || !fits(h.ncols) {
        return parse_with(data, file, opts)?.to_sparse();
    }
    let body = &data[h.data_offset..];
    let (entries, any_upper) = coordinate_entries::<(u32, u32, f64)>(body, &h, file, false)?;
    let e = entries.as_slice();
    let parts = match h.symmetry {
        // (a symmetric header is square: checked with the size line)
        Symmetry::Symmetric if !any_upper => [
            Part {
                entries: e,
                mirror: true,
            },
            Part::direct(e),
        ],
        Symmetry::General if !opts.require_symmetric => [Part::direct(e), Part::direct(&[])],
        _ => {
            let wide: Vec<(usize, usize, f64)> = e.iter().map(|x| x.get()).collect();
            drop(entries);
            let m = finish(wide, any_upper, &h, body, file, opts)?;
            return m.to_sparse();
        }
    };
    let col_ptr = column_starts(h.ncols, &parts);
    Ok(csc_from_parts(h.nrows, h.ncols, col_ptr, &parts))
}

/// Column starts (`n + 1` prefix sums) of the entries placed by `parts`; large inputs counted
/// in parallel blocks (integer sums: the same counts in any order).
fn column_starts<T: Slot>(n: usize, parts: &[Part<'_, T>]) -> Vec<usize> {
    let count = |part: Part<'_, T>, block: &[T], acc: &mut [usize]| {
        for &e in block {
            if let Some((_, c, _)) = placed(part, e) {
                acc[c + 1] += 1;
            }
        }
    };
    let total: usize = parts.iter().map(|p| p.entries.len()).sum();
    let threads = rayon::current_num_threads();
    let mut col_ptr = if total >= 1 << 20 && n.saturating_mul(threads) <= total / 4 {
        let block = total.div_ceil(2 * threads).max(1);
        let blocks: Vec<(Part<'_, T>, &[T])> = parts
            .iter()
            .flat_map(|&p| p.entries.chunks(block).map(move |b| (p, b)))
            .collect();
        blocks
            .into_par_iter()
            .fold(
                || vec![0usize; n + 1],
                |mut acc, (p, b)| {
                    count(p, b, &mut acc);
                    acc
                },
            )
            .reduce(
                || vec![0usize; n + 1],
                |mut a, b| {
                    a.iter_mut().zip(&b).for_each(|(x, y)| *x += y);
                    a
                },
            )
    } else {
        let mut acc = vec![0usize; n + 1];
        for &p in parts {
            count(p, p.entries, &mut acc);
        }
        acc
    };
    for j in 0..n {
        col_ptr[j + 1] += col_ptr[j];
    }
    col_ptr
}

/// Read a Matrix Market file straight into a CSC matrix ([`parse_sparse_with`]): the fastest
/// way to load a stiffness or mass matrix (about half the time of [`read_with`] followed by
/// [`MtxMatrix::to_sparse`] for the tire's K and M, `BENCHMARKS.md`). A directory or unreadable
/// path is a [`FeError::Io`] naming it. The file is memory-mapped (read into memory where it
/// cannot be): it must not be truncated by another process while it is read.
pub fn read_sparse_with(
    path: impl AsRef<Path>, opts: &ReadOptions,
) -> Result<SparseColMat<usize, f64>, FeError> {
    let (name, data) = super::map_bytes(path.as_ref())?;
    parse_sparse_with(&data, &name, opts)
}

/// Read a Matrix Market file with the default [`ReadOptions`].
pub fn read(path: impl AsRef<Path>) -> Result<MtxMatrix, FeError> {
    read_with(path, &ReadOptions::default())
}

/// Read a Matrix Market file with `opts` (a directory or unreadable path is a
/// [`FeError::Io`] naming it). The file is memory-mapped, as in [`read_sparse_with`].
pub fn read_with(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<MtxMatrix, FeError> {
    let (name, data) = super::map_bytes(path.as_ref())?;
    parse_with(&data, &name, opts)
}
