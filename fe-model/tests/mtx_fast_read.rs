//! The Matrix Market reader's fast paths (issue #16): the byte scanner of well-formed lines, the
//! parallel mirroring of symmetric files and the parallel CSC build, checked on a file large
//! enough for all three (> 4 MB, > 2²⁰ entries after mirroring) against independent references:
//! the lines parsed here with `str::split_whitespace` / `str::parse`, and faer's own triplet
//! constructor (which sums duplicates) for the CSC matrix.

use faer::sparse::{SparseColMat, Triplet};
use fe_model::FeError;
use fe_model::error::MatrixFileError as E;
use fe_model::io::mtx::{self, ReadOptions};

/// A symmetric coordinate file of order `n`, lower triangle column by column (so every column
/// of the expanded matrix is two ascending runs), with the line styles the scanner must treat
/// like the line-based parser: tabs, runs of blanks, trailing blanks, `\r\n`, leading zeros,
/// signed and exponent values, leading blanks (the line-based path), comment and blank lines
/// (including `%` lines inside the data), and duplicated positions with integer values (so
/// their sums are exact in any order).
fn big_symmetric(n: usize) -> (String, usize) {
    let mut body = String::new();
    let mut count = 0usize;
    for c in 0..n {
        for (k, r) in [c, c + 1, c + 7, c + 50].into_iter().enumerate() {
            if r >= n {
                continue;
            }
            let i = count;
            let v = if k == 1 {
                format!("{}", (i % 13) as f64 - 6.0)
            } else {
                format!("{:e}", 1.0 + i as f64 * 1.25e-3)
            };
            let line = match i % 11 {
                0 => format!("{}\t{}\t{v}\n", r + 1, c + 1),
                1 => format!("{}   {}  {v}   \n", r + 1, c + 1),
                2 => format!("{} {} {v}\r\n", r + 1, c + 1),
                3 if !v.starts_with('-') => format!("000{} 0{} +{v}\n", r + 1, c + 1),
                4 => format!("  {} {} {v}\n", r + 1, c + 1),
                _ => format!("{} {} {v}\n", r + 1, c + 1),
            };
            body += &line;
            count += 1;
            if k == 1 && c.is_multiple_of(5) {
                // a duplicate of the sub-diagonal entry (summed)
                body += &format!("{} {} 3\n", r + 1, c + 1);
                count += 1;
            }
            if i.is_multiple_of(997) {
                body += "% a comment inside the data\n\n   \n";
            }
        }
    }
    let text =
        format!("%%MatrixMarket matrix coordinate real symmetric\n% test\n{n} {n} {count}\n{body}");
    (text, count)
}

/// The data lines parsed here, independently: 0-based `(row, col, value)` in file order.
fn reference_entries(text: &str) -> Vec<(usize, usize, f64)> {
    let mut out = Vec::new();
    for line in text.lines().skip(3) {
        let t: Vec<&str> = line.split_whitespace().collect();
        if t.is_empty() || t[0].starts_with('%') {
            continue;
        }
        let r: usize = t[0].parse().unwrap();
        let c: usize = t[1].parse().unwrap();
        let v: f64 = t[2].parse().unwrap();
        out.push((r - 1, c - 1, v));
    }
    out
}

#[test]
fn fast_scanner_and_parallel_csc_match_independent_references() {
    let n = 320_000;
    let (text, count) = big_symmetric(n);
    assert!(text.len() > 1 << 22);
    let m = mtx::parse_with(text.as_bytes(), "big.mtx", &ReadOptions::symmetric()).unwrap();
    // entries: the file's, then the mirrors of the off-diagonal ones, both in file order
    let lower = reference_entries(&text);
    assert_eq!(lower.len(), count);
    let mut want = lower.clone();
    want.extend(
        lower
            .iter()
            .filter(|e| e.0 != e.1)
            .map(|&(r, c, v)| (c, r, v)),
    );
    assert!(want.len() > 1 << 20);
    assert_eq!(m.entries.len(), want.len());
    for (k, (a, b)) in m.entries.iter().zip(&want).enumerate() {
        assert!(
            a.0 == b.0 && a.1 == b.1 && a.2.to_bits() == b.2.to_bits(),
            "entry {k}: {a:?} vs {b:?}"
        );
    }
    // CSC: faer's triplet constructor sums the duplicates; all sums are of small integers
    let s = m.to_sparse().unwrap();
    let t: Vec<_> = want
        .iter()
        .map(|&(r, c, v)| Triplet::new(r, c, v))
        .collect();
    let f = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &t).unwrap();
    assert_same(&s, &f);
    // straight into CSC (compact entries, mirrored while filling), from the bytes and from a
    // memory-mapped file: the same matrix as faer's, bit for bit
    let d = mtx::parse_sparse_with(text.as_bytes(), "big.mtx", &ReadOptions::symmetric()).unwrap();
    assert_same(&d, &f);
    let path = std::env::temp_dir().join(format!("flowmbd-fast-read-{}.mtx", std::process::id()));
    std::fs::write(&path, &text).unwrap();
    let r = mtx::read_sparse_with(&path, &ReadOptions::symmetric());
    let w = mtx::read_with(&path, &ReadOptions::symmetric());
    std::fs::remove_file(&path).unwrap();
    assert_same(&r.unwrap(), &f);
    assert_eq!(w.unwrap(), m);
}

/// Same pattern and values, bit for bit.
fn assert_same(a: &SparseColMat<usize, f64>, b: &SparseColMat<usize, f64>) {
    assert_eq!((a.nrows(), a.ncols()), (b.nrows(), b.ncols()));
    assert_eq!(a.symbolic().col_ptr(), b.symbolic().col_ptr());
    assert_eq!(a.symbolic().row_idx(), b.symbolic().row_idx());
    assert_eq!(a.val().len(), b.val().len());
    for (x, y) in a.val().iter().zip(b.val()) {
        assert_eq!(x.to_bits(), y.to_bits());
    }
}

/// A `general` file large enough for the parallel paths (both triangles, columns listed out of
/// order, duplicates) read straight into CSC: faer's triplet constructor on the independently
/// parsed lines (`str::parse`) gives the same matrix, bit for bit; and the same file with an
/// entry above the diagonal under a `symmetric` header (the general mirroring path) matches
/// the two-step reading.
#[test]
fn straight_to_csc_matches_faer_triplets_for_general_files() {
    let n = 200_000;
    let mut body = String::new();
    let mut count = 0usize;
    for k in 0..n {
        // columns visited in a scrambled order, so columns are not ascending in the file
        let c = (k * 7919) % n;
        for r in [c, (c + 3) % n, (c + n - 11) % n] {
            body += &format!("{} {} {:e}\n", r + 1, c + 1, 1.0 + (k % 97) as f64 * 0.5);
            count += 1;
        }
        if k % 3 == 0 {
            body += &format!("{} {} -2\n", c + 1, c + 1);
            count += 1;
        }
    }
    let text = format!("%%MatrixMarket matrix coordinate real general\n{n} {n} {count}\n{body}");
    assert!(text.len() > 1 << 22);
    let t: Vec<_> = reference_entries(&format!("%\n{text}"))
        .into_iter()
        .map(|(r, c, v)| Triplet::new(r, c, v))
        .collect();
    assert_eq!(t.len(), count);
    let f = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &t).unwrap();
    let d = mtx::parse_sparse_with(text.as_bytes(), "g.mtx", &ReadOptions::default()).unwrap();
    assert_same(&d, &f);
    // a symmetric header with entries on both sides: mirrored and checked by the general path
    let (sym, _) = big_symmetric(100_000);
    let upper = sym.replacen("\n9 2 ", "\n2 9 ", 1);
    assert_ne!(upper, sym);
    let two_step = mtx::parse_with(upper.as_bytes(), "u.mtx", &ReadOptions::symmetric())
        .unwrap()
        .to_sparse()
        .unwrap();
    let d = mtx::parse_sparse_with(upper.as_bytes(), "u.mtx", &ReadOptions::symmetric()).unwrap();
    assert_same(&d, &two_step);
}

fn kind(r: Result<mtx::MtxMatrix, FeError>) -> (usize, E) {
    match r {
        Err(FeError::Matrix { line, kind, .. }) => (line, kind),
        other => panic!("expected a Matrix error, got {other:?}"),
    }
}

/// Lines the scanner leaves to the line-based parser keep their typed errors and true line
/// numbers, deep inside a file parsed in parallel chunks.
#[test]
fn malformed_lines_in_a_big_file_keep_their_errors_and_lines() {
    let (text, _) = big_symmetric(320_000);
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    // a data line about two thirds into the file, not a comment or blank one
    let mut at = 2 * lines.len() / 3;
    while lines[at].trim().is_empty() || lines[at].trim_start().starts_with('%') {
        at += 1;
    }
    let t: Vec<&str> = lines[at].split_whitespace().collect();
    type Check = fn(&E) -> bool;
    let cases: [(String, Check); 5] = [
        (format!("{} {} 1.5e\n", t[0], t[1]), |k| {
            matches!(k, E::Syntax(_))
        }),
        (format!("{} {} {} 4\n", t[0], t[1], t[2]), |k| {
            matches!(k, E::Syntax(_))
        }),
        (format!("{} {} inf\n", t[0], t[1]), |k| {
            matches!(k, E::NonFinite(_))
        }),
        (format!("320001 {} 1.0\n", t[1]), |k| {
            matches!(k, E::IndexOutOfRange { row: 320_001, .. })
        }),
        (format!("{}x {} 1.0\n", t[0], t[1]), |k| {
            matches!(k, E::Syntax(_))
        }),
    ];
    for (line, ok) in cases {
        let mut bad = lines.clone();
        bad[at] = &line;
        let data = bad.concat();
        let (l, k) = kind(mtx::parse_with(
            data.as_bytes(),
            "big.mtx",
            &ReadOptions::symmetric(),
        ));
        assert_eq!(l, at + 1, "`{}`", line.trim());
        assert!(ok(&k), "`{}`: {k}", line.trim());
        // the straight-to-CSC reader reports the same error at the same line
        match mtx::parse_sparse_with(data.as_bytes(), "big.mtx", &ReadOptions::symmetric()) {
            Err(FeError::Matrix { line: l2, kind, .. }) => {
                assert_eq!((l2, kind.to_string()), (l, k.to_string()));
            }
            other => panic!("expected a Matrix error, got {other:?}"),
        }
    }
}

/// A file of mostly blank and comment lines (parsed in parallel chunks, the slots sized by
/// bytes per entry, not lines) reads its few entries, in file order, with the declared count
/// checked.
#[test]
fn blank_line_padding_reads_the_entries() {
    let mut text = String::from("%%MatrixMarket matrix coordinate real general\n4 4 3\n");
    let pad = "\n".repeat(3 << 20) + &"%\n".repeat(1 << 19);
    for (r, c, v) in [(1, 1, 2.5), (4, 2, -1.0), (3, 3, 7.0)] {
        text += &pad;
        text += &format!("{r} {c} {v}\n");
    }
    assert!(text.len() > 1 << 22);
    let m = mtx::parse_with(text.as_bytes(), "pad.mtx", &ReadOptions::default()).unwrap();
    assert_eq!(m.entries, vec![(0, 0, 2.5), (3, 1, -1.0), (2, 2, 7.0)]);
    let short = text.replacen("4 4 3", "4 4 4", 1);
    let (_, k) = kind(mtx::parse_with(
        short.as_bytes(),
        "pad.mtx",
        &ReadOptions::default(),
    ));
    assert!(
        matches!(
            k,
            E::Truncated {
                expected: 4,
                found: 3
            }
        ),
        "{k}"
    );
}
