//! The banner and size line of a Matrix Market file, with the size ceiling checked before
//! anything is allocated.

use super::{Format, Symmetry};
use crate::FeError;
use crate::error::MatrixFileError as E;
use crate::io::{err, parsed};

/// Largest dimension any sparse matrix can hold here whatever the ceiling: its `n + 1` column
/// pointers and `n`-long work arrays must fit in `isize::MAX` bytes.
pub(super) const HARD_MAX_DIM: usize = (isize::MAX as usize) / 16;

/// What the header says, and where the data start.
#[derive(Debug, Clone)]
pub(super) struct Header {
    pub format: Format,
    pub symmetry: Symmetry,
    pub nrows: usize,
    pub ncols: usize,
    /// Declared entries (coordinate format; 0 for arrays).
    pub nnz: usize,
    /// 1-based line of the size line.
    pub size_line: usize,
    /// Byte offset of the first data line.
    pub data_offset: usize,
    /// 1-based line number of the first data line.
    pub data_line: usize,
}

/// A line for messages: lossy UTF-8, trimmed, at most 60 characters.
pub(super) fn show(line: &[u8]) -> String {
    let s = String::from_utf8_lossy(line);
    let s = s.trim();
    // control characters escaped (issue 35 item 7: no escape sequence reaches a terminal)
    match s.char_indices().nth(60) {
        Some((i, _)) => format!("{}…", mbd_core::validate::escape(&s[..i])),
        None => mbd_core::validate::escape(s),
    }
}

pub(super) fn skipped(line: &[u8]) -> bool {
    match line.iter().position(|b| !b.is_ascii_whitespace()) {
        None => true,
        Some(i) => line[i] == b'%',
    }
}

/// Next line of `data` from `*pos` (without the `\n`), advancing `*pos`.
fn next_line<'a>(data: &'a [u8], pos: &mut usize) -> Option<&'a [u8]> {
    if *pos >= data.len() {
        return None;
    }
    let rest = &data[*pos..];
    let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
    *pos += (end + 1).min(rest.len());
    Some(&rest[..end])
}

/// The value paired with the banner word `word` (`what`: object, format, field or symmetry) in
/// `table`, or the message "unsupported `what` `word`" followed by `hint`.
fn keyword<T: Copy>(word: &str, table: &[(&str, T)], what: &str, hint: &str) -> Result<T, String> {
    table
        .iter()
        .find(|(w, _)| *w == word)
        .map(|&(_, v)| v)
        .ok_or_else(|| {
            format!(
                "unsupported {what} `{}`{hint}",
                mbd_core::validate::escape(word)
            )
        })
}

/// Parse banner and size line; `max_dim` is the ceiling on rows and columns.
pub(super) fn parse(data: &[u8], file: &str, max_dim: usize) -> Result<Header, FeError> {
    let mut pos = 0usize;
    let banner =
        next_line(data, &mut pos).ok_or_else(|| err(file, 1, E::Header("empty file".into())))?;
    let b: Vec<String> = String::from_utf8_lossy(banner)
        .split_whitespace()
        .map(|s| s.to_ascii_lowercase())
        .collect();
    let header = |m: String| err(file, 1, E::Header(m));
    if b.len() != 5 || b[0] != "%%matrixmarket" {
        return Err(header(
            "expected `%%MatrixMarket matrix <format> <field> <symmetry>`".into(),
        ));
    }
    keyword(&b[1], &[("matrix", ())], "object", "").map_err(header)?;
    let format = keyword(
        &b[2],
        &[("coordinate", Format::Coordinate), ("array", Format::Array)],
        "format",
        "",
    )
    .map_err(header)?;
    keyword(
        &b[3],
        &[("real", ()), ("integer", ()), ("double", ())],
        "field",
        " (real or integer)",
    )
    .map_err(header)?;
    let symmetry = keyword(
        &b[4],
        &[
            ("general", Symmetry::General),
            ("symmetric", Symmetry::Symmetric),
        ],
        "symmetry",
        " (general or symmetric)",
    )
    .map_err(header)?;
    // comments and blank lines up to the size line
    let mut ln = 1usize;
    let size = loop {
        ln += 1;
        match next_line(data, &mut pos) {
            None => return Err(err(file, ln, E::Size("missing size line".into()))),
            Some(l) if skipped(l) => continue,
            Some(l) => break l,
        }
    };
    let text = String::from_utf8_lossy(size);
    let dims: Vec<&str> = text.split_whitespace().collect();
    let want = if format == Format::Coordinate { 3 } else { 2 };
    if dims.len() != want {
        return Err(err(
            file,
            ln,
            E::Size(format!("expected {want} integers, found `{}`", show(size))),
        ));
    }
    let mut d = [0usize; 3];
    for (i, t) in dims.iter().enumerate() {
        d[i] = parsed(t, "a non-negative integer below 2⁶⁴", E::Size, file, ln)?;
    }
    let (nrows, ncols) = (d[0], d[1]);
    let limit = max_dim.min(HARD_MAX_DIM);
    for (what, value) in [("rows", nrows), ("columns", ncols)] {
        if value > limit {
            return Err(err(
                file,
                ln,
                E::TooLarge {
                    what: what.into(),
                    value,
                    limit,
                    raisable: limit < HARD_MAX_DIM,
                },
            ));
        }
    }
    if symmetry == Symmetry::Symmetric && nrows != ncols {
        return Err(err(
            file,
            ln,
            E::Size(format!(
                "symmetric matrix must be square, got {nrows}×{ncols}"
            )),
        ));
    }
    // what reading will allocate at most, from the header and the data actually present (an
    // entry line has at least 6 bytes, an array value 2): compared with the memory available
    // before anything is allocated, even with the ceiling lifted (issue 35)
    let body = (data.len() - pos.min(data.len())) as f64;
    let bytes = match format {
        Format::Coordinate => {
            let entries = (d[2] as f64).min(body / 6.0 + 1.0);
            let mirror = if symmetry == Symmetry::Symmetric {
                2.0
            } else {
                1.0
            };
            8.0 * (ncols as f64 + 1.0) + entries * mirror * 40.0
        }
        Format::Array => {
            let values = (nrows as f64 * ncols as f64).min(body / 2.0 + 1.0);
            8.0 * (ncols as f64 + 1.0) + values * 2.0 * 40.0
        }
    };
    mbd_core::validate::limits::check_memory("matrix", bytes).map_err(|e| {
        err(
            file,
            ln,
            E::Size(format!(
                "{nrows}×{ncols} with {} entries {}",
                d[2], e.reason
            )),
        )
    })?;
    Ok(Header {
        format,
        symmetry,
        nrows,
        ncols,
        nnz: d[2],
        size_line: ln,
        data_offset: pos,
        data_line: ln + 1,
    })
}
