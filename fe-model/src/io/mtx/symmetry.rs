//! Symmetric storage: expansion of `symmetric` files to both triangles, and the checks of a
//! matrix that must be symmetric (module documentation of [`super`]).

use super::header::Header;
use super::scan::{data_line, value_line};
use super::{SYMMETRY_RTOL, Symmetry};
use crate::FeError;
use crate::error::MatrixFileError as E;
use crate::io::{check_mirror, err};
use rayon::prelude::*;

use super::scan::Entries;

/// Off-diagonal positions `(max, min)` with their two sides.
type Pairs = Vec<((usize, usize), Pair)>;

/// Sums of one position's entries stored below and above the diagonal, with the index (file
/// order) of the first entry of each side.
#[derive(Default)]
struct Pair {
    lower: Option<(f64, usize)>,
    upper: Option<(f64, usize)>,
}

/// Group the off-diagonal entries of `entries` by position `(max, min)`: for each, the sums of
/// the entries stored below and above the diagonal. Diagonal entries are returned apart with
/// their index. Sorted by column, then row, of the lower-triangle position.
fn pairs(entries: &[(usize, usize, f64)]) -> (Pairs, Vec<usize>) {
    let mut keyed: Vec<(usize, usize, usize)> = Vec::with_capacity(entries.len());
    let mut diagonal = Vec::new();
    for (k, &(r, c, _)) in entries.iter().enumerate() {
        if r == c {
            diagonal.push(k);
        } else {
            keyed.push((r.min(c), r.max(c), k));
        }
    }
    keyed.sort_unstable();
    let mut out: Pairs = Vec::new();
    for (lo, hi, k) in keyed {
        let (r, c, v) = entries[k];
        if out.last().is_none_or(|(key, _)| *key != (hi, lo)) {
            out.push(((hi, lo), Pair::default()));
        }
        let Some((_, p)) = out.last_mut() else {
            continue;
        };
        let side = if r > c { &mut p.lower } else { &mut p.upper };
        match side {
            Some((sum, _)) => *sum += v,
            None => *side = Some((v, k)),
        }
    }
    (out, diagonal)
}

/// Both triangles of a `symmetric` coordinate file. Entries all in the lower triangle (the
/// usual case) are mirrored directly; otherwise an entry given in both triangles must agree
/// with its mirror ([`check_mirror`], reported at the line of the later one) and duplicates on
/// one side are summed.
pub(super) fn expand(
    entries: Entries, any_upper: bool, data: &[u8], first_line: usize, file: &str,
) -> Result<Entries, FeError> {
    if !any_upper {
        // mirrors appended in place (no second copy of the entries), in file order; large
        // files in parallel blocks, each writing its mirrors at its offset
        let mut entries = entries;
        let len = entries.len();
        let block = (len / (4 * rayon::current_num_threads()).max(1)).max(1 << 16);
        let counts: Vec<usize> = entries
            .par_chunks(block)
            .map(|b| b.iter().filter(|e| e.0 != e.1).count())
            .collect();
        let off: usize = counts.iter().sum();
        entries.resize(len + off, (0, 0, 0.0));
        let (lower, mut upper) = entries.split_at_mut(len);
        let mut tasks = Vec::with_capacity(counts.len());
        for (b, &k) in lower.chunks(block).zip(&counts) {
            let (u0, u1) = upper.split_at_mut(k);
            tasks.push((b, u0));
            upper = u1;
        }
        tasks.into_par_iter().for_each(|(b, u)| {
            for (slot, &(r, c, v)) in u.iter_mut().zip(b.iter().filter(|e| e.0 != e.1)) {
                *slot = (c, r, v);
            }
        });
        return Ok(entries);
    }
    let (pairs, diagonal) = pairs(&entries);
    let mut out = Vec::with_capacity(2 * pairs.len() + diagonal.len());
    out.extend(diagonal.iter().map(|&k| entries[k]));
    for ((r, c), p) in pairs {
        let v = match (p.lower, p.upper) {
            (Some((a, ka)), Some((b, kb))) => {
                // the side seen first holds the value; the other is checked against it
                let (first, (second, k2)) = if ka < kb { (a, (b, kb)) } else { (b, (a, ka)) };
                let (r2, c2, _) = entries[k2];
                check_mirror(
                    file,
                    data_line(data, first_line, k2),
                    (r2, c2),
                    second,
                    first,
                )?;
                first
            }
            (Some((v, _)), None) | (None, Some((v, _))) => v,
            (None, None) => continue,
        };
        out.push((r, c, v));
        out.push((c, r, v));
    }
    Ok(out)
}

/// Check that a matrix read with [`super::ReadOptions::symmetric`] is square and symmetric.
/// `symmetric` files are by construction; a `general` one storing off-diagonal (non-zero)
/// entries on one side only is [`E::OneTriangle`] at line 1, and one whose entries differ from
/// their mirror by more than [`SYMMETRY_RTOL`] is [`E::NotSymmetric`] at the entry's line.
pub(super) fn require(
    entries: &[(usize, usize, f64)], h: &Header, data: &[u8], file: &str,
) -> Result<(), FeError> {
    if h.nrows != h.ncols {
        return Err(err(
            file,
            h.size_line,
            E::Size(format!(
                "a stiffness or mass matrix must be square, got {}×{}",
                h.nrows, h.ncols
            )),
        ));
    }
    if h.symmetry == Symmetry::Symmetric {
        return Ok(());
    }
    let (mut lower, mut upper) = (0usize, 0usize);
    let mut scale = 0.0f64;
    for &(r, c, v) in entries {
        scale = scale.max(v.abs());
        if v != 0.0 {
            if r > c {
                lower += 1;
            } else if r < c {
                upper += 1;
            }
        }
    }
    if (lower == 0) != (upper == 0) {
        let (stored, count) = if lower > 0 {
            ("lower", lower)
        } else {
            ("upper", upper)
        };
        return Err(err(file, 1, E::OneTriangle { stored, count }));
    }
    // a `general` file has one entry per data line (coordinate) or per value (array)
    let line = |k: usize| match h.format {
        super::Format::Coordinate => data_line(data, h.data_line, k),
        super::Format::Array => value_line(data, h.data_line, k),
    };
    let (pairs, _) = pairs(entries);
    for (_, p) in pairs {
        let a = p.lower.map_or(0.0, |x| x.0);
        let b = p.upper.map_or(0.0, |x| x.0);
        if (a - b).abs() > SYMMETRY_RTOL * a.abs().max(b.abs()) + 1e-14 * scale {
            // report the entry that is present (both, the lower one)
            let k = p.lower.or(p.upper).map_or(0, |x| x.1);
            let (r, c, _) = entries[k];
            let (value, mirror) = if r > c { (a, b) } else { (b, a) };
            return Err(err(
                file,
                line(k),
                E::NotSymmetric {
                    row: r + 1,
                    col: c + 1,
                    value,
                    mirror,
                },
            ));
        }
    }
    Ok(())
}
