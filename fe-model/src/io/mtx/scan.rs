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

/// One parsed entry as the scanner stores it: the public `(usize, usize, f64)` (24 bytes) or
/// the compact `(u32, u32, f64)` (16 bytes) of the direct CSC reader (matrices of at most
/// `u32::MAX` rows and columns).
pub(super) trait Slot: Copy + Send + Sync {
    /// The zero entry; `vec![ZERO; n]` of a tuple of primitives is a zeroed allocation (no
    /// memset pass over the array).
    const ZERO: Self;
    /// From a 0-based entry whose indices fit.
    fn new(r: usize, c: usize, v: f64) -> Self;
    /// 0-based `(row, col, value)`.
    fn get(self) -> (usize, usize, f64);
}

impl Slot for (usize, usize, f64) {
    const ZERO: Self = (0, 0, 0.0);
    #[inline]
    fn new(r: usize, c: usize, v: f64) -> Self {
        (r, c, v)
    }
    #[inline]
    fn get(self) -> (usize, usize, f64) {
        self
    }
}

impl Slot for (u32, u32, f64) {
    const ZERO: Self = (0, 0, 0.0);
    #[inline]
    fn new(r: usize, c: usize, v: f64) -> Self {
        // callers read only matrices of at most `u32::MAX` rows and columns
        (r as u32, c as u32, v)
    }
    #[inline]
    fn get(self) -> (usize, usize, f64) {
        (self.0 as usize, self.1 as usize, self.2)
    }
}

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

/// Decimal digits `[0-9]+` at `*pos` (at most 18, so no overflow), advancing `*pos`.
#[inline]
fn digits(data: &[u8], pos: &mut usize) -> Option<u64> {
    let start = *pos;
    let mut i = start;
    let mut v = 0u64;
    while let Some(&b) = data.get(i) {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        v = v * 10 + u64::from(d);
        i += 1;
        if i - start > 18 {
            return None;
        }
    }
    if i == start {
        return None;
    }
    *pos = i;
    Some(v)
}

/// Skip spaces and tabs at `*pos`; whether there was at least one.
#[inline]
fn blanks(data: &[u8], pos: &mut usize) -> bool {
    let start = *pos;
    while matches!(data.get(*pos), Some(b' ' | b'\t')) {
        *pos += 1;
    }
    *pos > start
}

/// The reader's hot loop: a well-formed `row col value` line starting at `p` (digits, blanks,
/// digits, blanks, a finite number, optional trailing blanks, then `\n` or the end). Returns
/// the 0-based entry and the position after the line, or `None` for anything else (a
/// comment, a blank line, a malformed or out-of-range line), which the line-based
/// [`entry`] then handles with its typed error: both accept the same well-formed lines.
#[inline]
fn fast_entry(
    data: &[u8], mut p: usize, nrows: u64, ncols: u64,
) -> Option<((usize, usize, f64), usize)> {
    let r = digits(data, &mut p)?;
    if !blanks(data, &mut p) {
        return None;
    }
    let c = digits(data, &mut p)?;
    if !blanks(data, &mut p) {
        return None;
    }
    let (v, n) = fast_float2::parse_partial::<f64, _>(data.get(p..)?).ok()?;
    p += n;
    while matches!(data.get(p), Some(b' ' | b'\t' | b'\r')) {
        p += 1;
    }
    match data.get(p) {
        None => {}
        Some(b'\n') => p += 1,
        Some(_) => return None,
    }
    if r == 0 || c == 0 || r > nrows || c > ncols || !v.is_finite() {
        return None;
    }
    Some(((r as usize - 1, c as usize - 1, v), p))
}

/// What one chunk yields: the number of entries it wrote to the front of its slot (up to its
/// first error), whether any lies above the diagonal, and the error with its 0-based line
/// index within the chunk.
struct Chunk {
    count: usize,
    any_upper: bool,
    error: Option<(usize, E)>,
}

/// Lines of `data` that can hold an entry: its newlines, plus an unterminated last line. A
/// chunk never yields more entries than this (one per line).
fn line_bound(data: &[u8]) -> usize {
    // byte counts summed in blocks that cannot overflow a u8 (vectorised by the compiler)
    let newlines: usize = data
        .chunks(192)
        .map(|b| {
            b.iter()
                .fold(0u8, |n, &x| n.wrapping_add(u8::from(x == b'\n'))) as usize
        })
        .sum();
    newlines + usize::from(data.last().is_some_and(|&b| b != b'\n'))
}

/// Parse the lines of `data` into the front of `slot` (of `min(line_bound, len / 6 + 1)`
/// entries: one per line, each line of an entry at least 6 bytes with its newline).
fn parse_chunk<T: Slot>(data: &[u8], slot: &mut [T], nrows: usize, ncols: usize) -> Chunk {
    let mut out = Chunk {
        count: 0,
        any_upper: false,
        error: None,
    };
    let (nr, nc) = (nrows as u64, ncols as u64);
    let mut p = 0usize;
    let mut line = 0usize;
    while p < data.len() {
        let e = match fast_entry(data, p, nr, nc) {
            Some((e, next)) => {
                p = next;
                e
            }
            None => {
                let end = data[p..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(data.len(), |k| p + k);
                let l = &data[p..end];
                p = end + 1;
                if skipped(l) {
                    line += 1;
                    continue;
                }
                match entry(l, nrows, ncols) {
                    Ok(e) => e,
                    Err(e) => {
                        out.error = Some((line, e));
                        break;
                    }
                }
            }
        };
        line += 1;
        // one entry per line of at least 6 bytes: `slot` has room for all of them
        let Some(s) = slot.get_mut(out.count) else {
            break;
        };
        *s = T::new(e.0, e.1, e.2);
        out.count += 1;
        out.any_upper |= e.0 < e.1;
    }
    out
}

/// Newline-aligned chunk boundaries of `data`.
fn chunks(data: &[u8]) -> Vec<(usize, usize)> {
    let n = if data.len() > PARALLEL_BYTES {
        // chunks of about 1 MiB, at least two per thread: small enough that a thread left
        // waiting on a busy machine takes over the others' work
        (2 * rayon::current_num_threads())
            .max(2)
            .max(data.len() >> 20)
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
///
/// The entries are parsed straight into one array sized by the file (its lines, not the
/// header's count): each chunk fills its own part in parallel, and the parts are then closed
/// up in place (they have gaps only where a chunk had comments or blank lines).
#[allow(clippy::too_many_arguments)]
pub(super) fn coordinate<T: Slot>(
    data: &[u8], first_line: usize, size_line: usize, nrows: usize, ncols: usize, nnz: usize,
    file: &str, mirror_room: bool,
) -> Result<(Vec<T>, bool), FeError> {
    let bounds = chunks(data);
    // a chunk's entries: at most one per line, and each takes at least `1 1 1` and a newline
    // (6 bytes), so memory stays proportional to the file even for one of blank lines
    let caps: Vec<usize> = bounds
        .par_iter()
        .map(|&(a, b)| line_bound(&data[a..b]).min((b - a) / 6 + 1))
        .collect();
    let lines: usize = caps.iter().sum();
    let mut all: Vec<T> = if mirror_room {
        let mut v = Vec::with_capacity(2 * lines);
        v.resize(lines, T::ZERO);
        v
    } else {
        vec![T::ZERO; lines]
    };
    let mut slots = Vec::with_capacity(caps.len());
    let mut rest = all.as_mut_slice();
    for &c in &caps {
        let (s, r) = rest.split_at_mut(c);
        slots.push(s);
        rest = r;
    }
    let parsed: Vec<Chunk> = bounds
        .par_iter()
        .zip(slots.into_par_iter())
        .map(|(&(a, b), slot)| parse_chunk(&data[a..b], slot, nrows, ncols))
        .collect();
    let mut total = 0usize;
    let mut any_upper = false;
    for (chunk, &(start, _)) in parsed.iter().zip(&bounds) {
        total += chunk.count;
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
    // close up the chunks' parts (in place, front to back)
    let (mut w, mut off) = (0usize, 0usize);
    for (chunk, &cap) in parsed.iter().zip(&caps) {
        if off != w {
            all.copy_within(off..off + chunk.count, w);
        }
        w += chunk.count;
        off += cap;
    }
    all.truncate(w);
    Ok((all, any_upper))
}

/// Parse the values of an array file (column-major; symmetric: lower triangle column by
/// column) into entries, mirrored for symmetric files. The declared size is compared with the
/// values found after reading, so nothing is allocated from the header.
pub(super) fn array(
    data: &[u8], first_line: usize, size_line: usize, h: &Header, file: &str,
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
