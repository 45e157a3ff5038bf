//! The data lines of a Matrix Market file: `row col value` triplets (coordinate) or values
//! (array), parsed from bytes. Coordinate files above [`PARALLEL_BYTES`] are split at newlines
//! into chunks parsed in parallel; the first error in file order wins, so the outcome is that of
//! a sequential read.

use super::Symmetry;
use super::header::{Header, show, skipped};
use crate::FeError;
use crate::error::MatrixFileError as E;
use crate::io::err;
use rayon::prelude::*;

/// 0-based `(row, col, value)` entries in file order.
pub(super) type Entries = Vec<(usize, usize, f64)>;

/// Data sections larger than this many bytes are parsed in parallel chunks.
const PARALLEL_BYTES: usize = 1 << 22;

/// Lines of `data` split at `\n` (a trailing newline gives a last, blank, line).
fn lines(data: &[u8]) -> impl Iterator<Item = &[u8]> {
    data.split(|&b| b == b'\n')
}

/// 1-based line number of the `k`-th (0-based) data line (not blank, not a comment) of `data`,
/// whose first line is `first_line`; the line after the last one if there are fewer.
pub(super) fn data_line(data: &[u8], first_line: usize, k: usize) -> usize {
    let mut seen = 0usize;
    let mut ln = first_line;
    for l in data.split(|&b| b == b'\n') {
        if !skipped(l) {
            if seen == k {
                return ln;
            }
            seen += 1;
        }
        ln += 1;
    }
    ln
}

/// 1-based line number of the `k`-th (0-based) value of an array file's `data`.
pub(super) fn value_line(data: &[u8], first_line: usize, k: usize) -> usize {
    let mut seen = 0usize;
    let mut ln = first_line;
    for l in lines(data) {
        if !skipped(l) {
            seen += tokens(l).count();
            if seen > k {
                return ln;
            }
        }
        ln += 1;
    }
    ln
}

/// Whitespace-separated tokens of a line.
fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// A signed decimal integer (`[+-]?[0-9]+`, as `i64`).
fn integer(tok: &[u8]) -> Option<i64> {
    let (neg, digits) = match tok.first()? {
        b'-' => (true, &tok[1..]),
        b'+' => (false, &tok[1..]),
        _ => (false, tok),
    };
    if digits.is_empty() {
        return None;
    }
    let mut v = 0i64;
    for &b in digits {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        v = v.checked_mul(10)?.checked_add(i64::from(d))?;
    }
    Some(if neg { -v } else { v })
}

/// A finite value (`fast-float2`, the Eisel–Lemire parser on the bytes: no UTF-8 pass; the
/// whole token must be the number).
fn value(tok: &[u8]) -> Result<f64, E> {
    let v: f64 = fast_float2::parse(tok)
        .map_err(|_| E::Syntax(format!("`{}` is not a number", show(tok))))?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(E::NonFinite(show(tok)))
    }
}

/// The next whitespace-separated token of `line` from `*pos` (advancing it).
#[inline]
fn next_token<'a>(line: &'a [u8], pos: &mut usize) -> Option<&'a [u8]> {
    let mut i = *pos;
    while i < line.len() && line[i].is_ascii_whitespace() {
        i += 1;
    }
    let start = i;
    while i < line.len() && !line[i].is_ascii_whitespace() {
        i += 1;
    }
    *pos = i;
    (i > start).then(|| &line[start..i])
}

/// One `row col value` line → 0-based entry (hand-scanned: this is the reader's hot loop).
fn entry(line: &[u8], nrows: usize, ncols: usize) -> Result<(usize, usize, f64), E> {
    let mut p = 0usize;
    let (Some(a), Some(b), Some(v), None) = (
        next_token(line, &mut p),
        next_token(line, &mut p),
        next_token(line, &mut p),
        next_token(line, &mut p),
    ) else {
        return Err(E::Syntax(format!(
            "expected `row col value`, found `{}`",
            show(line)
        )));
    };
    let idx = |s: &[u8]| {
        integer(s).ok_or_else(|| E::Syntax(format!("`{}` is not an integer index", show(s))))
    };
    let (r, c) = (idx(a)?, idx(b)?);
    if r < 1 || c < 1 || r as u64 > nrows as u64 || c as u64 > ncols as u64 {
        return Err(E::IndexOutOfRange {
            row: r,
            col: c,
            nrows,
            ncols,
        });
    }
    let v = value(v)?;
    Ok((r as usize - 1, c as usize - 1, v))
}

/// What one chunk yields: its entries up to its first error, whether any lies above the
/// diagonal, and the error with its 0-based line index within the chunk.
struct Chunk {
    entries: Vec<(usize, usize, f64)>,
    any_upper: bool,
    error: Option<(usize, E)>,
}

fn parse_chunk(data: &[u8], nrows: usize, ncols: usize) -> Chunk {
    // about 30 bytes per `row col value` line; never more than the chunk can hold
    let mut out = Chunk {
        entries: Vec::with_capacity(data.len() / 24),
        any_upper: false,
        error: None,
    };
    for (i, l) in lines(data).enumerate() {
        if skipped(l) {
            continue;
        }
        match entry(l, nrows, ncols) {
            Ok(e) => {
                out.any_upper |= e.0 < e.1;
                out.entries.push(e);
            }
            Err(e) => {
                out.error = Some((i, e));
                break;
            }
        }
    }
    out
}

/// Newline-aligned chunk boundaries of `data`.
fn chunks(data: &[u8]) -> Vec<(usize, usize)> {
    let n = if data.len() > PARALLEL_BYTES {
        (2 * rayon::current_num_threads()).max(2)
    } else {
        1
    };
    let mut out = Vec::with_capacity(n);
    let mut start = 0usize;
    for k in 1..=n {
        let mut end = if k == n {
            data.len()
        } else {
            (data.len() * k / n).max(start)
        };
        while end < data.len() && data[end - 1] != b'\n' {
            end += 1;
        }
        out.push((start, end));
        start = end;
    }
    out
}

/// Parse the triplets of a coordinate file (`data` starts at line `first_line`, after the
/// size line `size_line`) and compare their number with the declared `nnz`. Returns the
/// entries in file order and whether any lies above the diagonal. With `mirror_room` the
/// result has capacity for twice the entries (a symmetric file's mirrors are appended in
/// place without reallocating).
#[allow(clippy::too_many_arguments)]
pub(super) fn coordinate(
    data: &[u8],
    first_line: usize,
    size_line: usize,
    nrows: usize,
    ncols: usize,
    nnz: usize,
    file: &str,
    mirror_room: bool,
) -> Result<(Entries, bool), FeError> {
    let bounds = chunks(data);
    let parsed: Vec<Chunk> = bounds
        .par_iter()
        .map(|&(a, b)| parse_chunk(&data[a..b], nrows, ncols))
        .collect();
    let mut total = 0usize;
    let mut any_upper = false;
    for (chunk, &(start, _)) in parsed.iter().zip(&bounds) {
        total += chunk.entries.len();
        any_upper |= chunk.any_upper;
        if total > nnz {
            break;
        }
        if let Some((i, e)) = &chunk.error {
            if total == nnz {
                // the offending line is the (nnz+1)-th data line: one too many, whatever it says
                break;
            }
            let before = data[..start].iter().filter(|&&b| b == b'\n').count();
            return Err(err(file, first_line + before + i, e.clone()));
        }
    }
    let has_more = total > nnz || parsed.iter().any(|c| c.error.is_some());
    if has_more {
        return Err(err(
            file,
            data_line(data, first_line, nnz),
            E::TooManyEntries { expected: nnz },
        ));
    }
    if total < nnz {
        let line = if total == 0 {
            size_line + 1
        } else {
            data_line(data, first_line, total - 1) + 1
        };
        return Err(err(
            file,
            line,
            E::Truncated {
                expected: nnz,
                found: total,
            },
        ));
    }
    let entries = if parsed.len() == 1 {
        parsed
            .into_iter()
            .next()
            .map(|c| c.entries)
            .unwrap_or_default()
    } else {
        // `total` entries were parsed (not a count from the header)
        let mut all = Vec::with_capacity(if mirror_room { 2 * total } else { total });
        for c in parsed {
            all.extend(c.entries);
        }
        all
    };
    Ok((entries, any_upper))
}

/// Parse the values of an array file (column-major; symmetric: lower triangle column by
/// column) into entries, mirrored for symmetric files. The declared size is compared with the
/// values found after reading, so nothing is allocated from the header.
pub(super) fn array(
    data: &[u8],
    first_line: usize,
    size_line: usize,
    h: &Header,
    file: &str,
) -> Result<Vec<(usize, usize, f64)>, FeError> {
    let (nrows, ncols) = (h.nrows, h.ncols);
    // position of the next value; `None` once all declared positions are filled
    let first = |c: usize| {
        if h.symmetry == Symmetry::Symmetric {
            c
        } else {
            0
        }
    };
    let start = |c: usize| (c < ncols && first(c) < nrows).then(|| (first(c), c));
    let mut pos = start(0);
    let expected = || match h.symmetry {
        Symmetry::General => nrows.checked_mul(ncols),
        Symmetry::Symmetric => nrows.checked_mul(nrows + 1).map(|x| x / 2),
    };
    let mut entries = Vec::new();
    let mut found = 0usize;
    let mut last_line = size_line;
    for (i, l) in lines(data).enumerate() {
        if skipped(l) {
            continue;
        }
        let ln = first_line + i;
        last_line = ln;
        for tok in tokens(l) {
            let Some((r, c)) = pos else {
                return Err(err(
                    file,
                    ln,
                    E::TooManyEntries {
                        expected: expected().unwrap_or(found),
                    },
                ));
            };
            let v = value(tok).map_err(|e| err(file, ln, e))?;
            entries.push((r, c, v));
            if h.symmetry == Symmetry::Symmetric && r != c {
                entries.push((c, r, v));
            }
            found += 1;
            pos = if r + 1 < nrows {
                Some((r + 1, c))
            } else {
                start(c + 1)
            };
        }
    }
    if pos.is_some() {
        return Err(err(
            file,
            last_line + 1,
            E::Truncated {
                // the declared count can exceed usize only for a file far too short anyway
                expected: expected().unwrap_or(usize::MAX),
                found,
            },
        ));
    }
    Ok(entries)
}
