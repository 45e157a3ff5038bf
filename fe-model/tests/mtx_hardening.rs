//! Hardening of the Matrix Market reader (issue #20): headers that claim absurd sizes, `general`
//! files storing one triangle of a symmetric matrix, the parallel parse reporting the same first
//! error and line as a sequential read, and property tests (a few thousand random and mutated
//! files) that the reader never panics and round-trips exactly.

use fe_model::FeError;
use fe_model::error::MatrixFileError as E;
use fe_model::io::mtx::{self, ReadOptions};
use proptest::prelude::*;

fn kind(r: Result<mtx::MtxMatrix, FeError>) -> (usize, E) {
    match r {
        Err(FeError::Matrix { line, kind, .. }) => (line, kind),
        other => panic!("expected a Matrix error, got {other:?}"),
    }
}

fn parse(text: &str, opts: &ReadOptions) -> Result<mtx::MtxMatrix, FeError> {
    mtx::parse_with(text.as_bytes(), "t.mtx", opts)
}

/// Reproducers of issue #20 (each aborted or panicked before): refused at the size line, or
/// found short, without allocating what the header claims.
#[test]
fn absurd_headers_are_refused_before_allocating() {
    let d = ReadOptions::default();
    let (l, k) = kind(parse(
        "%%MatrixMarket matrix array real general\n18446744073709551615 2\n1\n",
        &d,
    ));
    assert_eq!(l, 2);
    assert!(matches!(k, E::TooLarge { raisable: true, .. }), "{k}");
    // 10^6 × 10^6 array: within the ceiling, so it is the data that is short (10^12 declared)
    let (l, k) = kind(parse(
        "%%MatrixMarket matrix array real general\n1000000 1000000\n1\n2\n",
        &d,
    ));
    assert_eq!(l, 5);
    assert!(matches!(k, E::Truncated { found: 2, .. }), "{k}");
    let (l, k) = kind(parse(
        "%%MatrixMarket matrix coordinate real symmetric\n100000000 100000000 100000000\n1 1 1\n",
        &d,
    ));
    assert_eq!(l, 2);
    assert!(
        matches!(
            k,
            E::TooLarge {
                value: 100_000_000,
                ..
            }
        ),
        "{k}"
    );
    // lifting the ceiling reads the 10^8 header; the declared count is checked against the data
    let (l, k) = kind(parse(
        "%%MatrixMarket matrix coordinate real symmetric\n100000000 100000000 100000000\n1 1 1\n",
        &d.allow_large(true),
    ));
    assert_eq!(l, 4);
    assert!(matches!(k, E::Truncated { found: 1, .. }), "{k}");
    // even with the ceiling lifted, a size no sparse matrix can index is refused
    let (_, k) = kind(parse(
        "%%MatrixMarket matrix coordinate real general\n18446744073709551615 1 0\n",
        &d.allow_large(true),
    ));
    assert!(
        matches!(
            k,
            E::TooLarge {
                raisable: false,
                ..
            }
        ),
        "{k}"
    );
    // a size past 2^64 is a size-line error, not an overflow
    let (l, k) = kind(parse(
        "%%MatrixMarket matrix coordinate real general\n99999999999999999999999 1 0\n",
        &d,
    ));
    assert_eq!(l, 2);
    assert!(matches!(k, E::Size(_)), "{k}");
}

/// K = k [[2, −1], [−1, 2]], M = m I: λ = k/m and 3k/m (analytical). Stored as the lower
/// triangle under `general` (the export slip of issue #20, which read as the triangular
/// [[2, 0], [−1, 2]] with λ = 2, 2) it is refused at line 1 when a symmetric matrix is required;
/// with `symmetric` in the header the analytical eigenvalues come back.
#[test]
fn one_triangle_general_is_refused_and_the_symmetric_header_gives_the_analytical_modes() {
    let lower = "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 2\n2 1 -1\n2 2 2\n";
    let (l, k) = kind(parse(lower, &ReadOptions::symmetric()));
    assert_eq!(l, 1);
    assert!(
        matches!(
            k,
            E::OneTriangle {
                stored: "lower",
                count: 1
            }
        ),
        "{k}"
    );
    assert!(k.to_string().contains("write `symmetric`"), "{k}");
    let upper = "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 2\n1 2 -1\n2 2 2\n";
    assert!(matches!(
        kind(parse(upper, &ReadOptions::symmetric())).1,
        E::OneTriangle {
            stored: "upper",
            ..
        }
    ));
    // an ordinary (non-symmetric) reader still reads a triangular matrix as such
    assert_eq!(
        parse(lower, &ReadOptions::default()).unwrap().entries.len(),
        3
    );
    let sym = lower.replace("general", "symmetric");
    let k = parse(&sym, &ReadOptions::symmetric()).unwrap().to_dense();
    let m = faer::Mat::<f64>::identity(2, 2);
    let modes = fe_model::dense_modes(k.as_ref(), m.as_ref(), 2).unwrap();
    assert!((modes.values[0] - 1.0).abs() < 1e-12 && (modes.values[1] - 3.0).abs() < 1e-12);
    // both triangles under `general`, differing: the entry and its line are named
    let bad =
        "%%MatrixMarket matrix coordinate real general\n2 2 4\n1 1 2\n2 1 -1\n1 2 -1.5\n2 2 2\n";
    let (l, k) = kind(parse(bad, &ReadOptions::symmetric()));
    assert_eq!(l, 4);
    assert!(matches!(k, E::NotSymmetric { row: 2, col: 1, .. }), "{k}");
    // agreeing to 1e-12 (printed digits) is accepted
    let ok = bad.replace("-1.5", "-1.000000000001");
    assert!(parse(&ok, &ReadOptions::symmetric()).is_ok());
    // a dense array storing only the lower triangle under `general`
    let arr = "%%MatrixMarket matrix array real general\n2 2\n2\n-1\n0\n2\n";
    assert!(matches!(
        kind(parse(arr, &ReadOptions::symmetric())).1,
        E::OneTriangle { .. }
    ));
}

/// A file large enough for the parallel parse (> 4 MB): entries in file order, and an error
/// deep inside reported at its true line, as a sequential read would.
#[test]
fn parallel_parse_matches_the_file_and_reports_true_lines() {
    let n = 200_000usize;
    let mut text = format!("%%MatrixMarket matrix coordinate real general\n% big\n{n} {n} {n}\n");
    for i in 0..n {
        text += &format!("{} {} {:e}\n", i + 1, (i * 7919) % n + 1, 0.1 + i as f64);
    }
    assert!(text.len() > 1 << 22);
    let m = parse(&text, &ReadOptions::default()).unwrap();
    assert_eq!(m.entries.len(), n);
    for (i, &(r, c, v)) in m.entries.iter().enumerate() {
        assert_eq!((r, c, v), (i, (i * 7919) % n, 0.1 + i as f64));
    }
    // break the entry on line 3 + 150001 (data line 150001)
    let bad = text.replacen(
        &format!("150001 {} ", (150_000 * 7919) % n + 1),
        "150001 x ",
        1,
    );
    let (l, k) = kind(parse(&bad, &ReadOptions::default()));
    assert_eq!(l, 3 + 150_001);
    assert!(matches!(k, E::Syntax(_)), "{k}");
    // one entry too many: named at the first extra line
    let extra = text.clone() + "1 1 1.0\n";
    let (l, k) = kind(parse(&extra, &ReadOptions::default()));
    assert_eq!(l, 3 + n + 1);
    assert!(
        matches!(k, E::TooManyEntries { expected } if expected == n),
        "{k}"
    );
}

fn coordinate(n: usize, entries: &[(usize, usize, f64)], sym: &str) -> String {
    let mut s = format!(
        "%%MatrixMarket matrix coordinate real {sym}\n{n} {n} {}\n",
        entries.len()
    );
    for &(r, c, v) in entries {
        s += &format!("{} {} {v:?}\n", r + 1, c + 1);
    }
    s
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Arbitrary bytes after a valid banner never panic.
    #[test]
    fn random_bodies_never_panic(body in proptest::collection::vec(any::<u8>(), 0..200),
                                 sym in prop_oneof![Just("general"), Just("symmetric")],
                                 fmt in prop_oneof![Just("coordinate"), Just("array")]) {
        let mut data = format!("%%MatrixMarket matrix {fmt} real {sym}\n").into_bytes();
        data.extend(body);
        for opts in [ReadOptions::default(), ReadOptions::symmetric()] {
            let _ = mtx::parse_with(&data, "f", &opts);
        }
    }

    /// Valid files with one token replaced by a random one (numbers of every size included)
    /// give a matrix or a typed error, never a panic; a parsed matrix has its entries in range.
    #[test]
    fn mutated_files_never_panic(n in 1usize..6,
                                 raw in proptest::collection::vec((0usize..6, 0usize..6, -1e3f64..1e3), 0..10),
                                 pos in any::<prop::sample::Index>(),
                                 token in prop_oneof![
                                     Just("18446744073709551615".to_string()),
                                     Just("-1".to_string()), Just("0".to_string()),
                                     Just("NaN".to_string()), Just("1e400".to_string()),
                                     Just("%".to_string()), Just("".to_string()),
                                     any::<u64>().prop_map(|x| x.to_string()),
                                     "[ -~]{0,6}",
                                 ]) {
        let entries: Vec<_> = raw.into_iter().map(|(r, c, v)| (r % n, c % n, v)).collect();
        let text = coordinate(n, &entries, "general");
        let mut toks: Vec<String> = text.split(' ').map(str::to_string).collect();
        let i = pos.index(toks.len());
        toks[i] = token;
        let data = toks.join(" ");
        if let Ok(m) = mtx::parse_with(data.as_bytes(), "f", &ReadOptions::symmetric()) {
            prop_assert!(m.entries.iter().all(|&(r, c, _)| r < m.nrows && c < m.ncols));
        }
        let _ = mtx::parse(&data, "f");
    }

    /// The straight-to-CSC reader and the two-step one (entries, then `to_sparse`) agree on
    /// any valid or mutated small file, general or symmetric (duplicates, entries on both
    /// sides, tokens replaced): the same matrix bit for bit, or the same error at the same
    /// line (second formulation of the same reading).
    #[test]
    fn straight_to_csc_agrees_with_the_two_step_reading(n in 1usize..6,
                                 raw in proptest::collection::vec((0usize..6, 0usize..6, -1e3f64..1e3), 0..12),
                                 sym in prop_oneof![Just("general"), Just("symmetric")],
                                 lower in any::<bool>(),
                                 pos in any::<prop::sample::Index>(),
                                 mutate in any::<bool>(),
                                 token in prop_oneof![
                                     Just("-1".to_string()), Just("0".to_string()),
                                     Just("NaN".to_string()), Just("%".to_string()),
                                     any::<u64>().prop_map(|x| x.to_string()),
                                     "[ -~]{0,6}",
                                 ]) {
        let entries: Vec<_> = raw
            .into_iter()
            .map(|(r, c, v)| {
                let (r, c) = (r % n, c % n);
                if lower { (r.max(c), r.min(c), v) } else { (r, c, v) }
            })
            .collect();
        let mut data = coordinate(n, &entries, sym);
        if mutate {
            let mut toks: Vec<String> = data.split(' ').map(str::to_string).collect();
            let i = pos.index(toks.len());
            toks[i] = token;
            data = toks.join(" ");
        }
        for opts in [ReadOptions::default(), ReadOptions::symmetric()] {
            let two = mtx::parse_with(data.as_bytes(), "f", &opts).and_then(|m| m.to_sparse());
            let one = mtx::parse_sparse_with(data.as_bytes(), "f", &opts);
            match (one, two) {
                (Ok(a), Ok(b)) => {
                    prop_assert_eq!(a.symbolic().col_ptr(), b.symbolic().col_ptr());
                    prop_assert_eq!(a.symbolic().row_idx(), b.symbolic().row_idx());
                    let bits = |m: &faer::sparse::SparseColMat<usize, f64>| {
                        m.val().iter().map(|v| v.to_bits()).collect::<Vec<_>>()
                    };
                    prop_assert_eq!(bits(&a), bits(&b));
                }
                (Err(a), Err(b)) => prop_assert_eq!(a.to_string(), b.to_string()),
                (a, b) => prop_assert!(false, "{:?} vs {:?}", a.map(|_| ()), b.map(|_| ())),
            }
        }
    }

    /// Symmetric storage written as its lower triangle reads back to the same full matrix,
    /// bit for bit (second formulation: the entries as generated, mirrored here).
    #[test]
    fn symmetric_round_trip_is_exact(n in 1usize..8,
                                     raw in proptest::collection::vec((0usize..8, 0usize..8, -1e6f64..1e6), 1..20)) {
        let mut want = std::collections::BTreeMap::new();
        for (r, c, v) in raw {
            let (r, c) = ((r % n).max(c % n), (r % n).min(c % n));
            want.insert((r, c), v);
        }
        let lower: Vec<_> = want.iter().map(|(&(r, c), &v)| (r, c, v)).collect();
        let m = mtx::parse(&coordinate(n, &lower, "symmetric"), "f").unwrap();
        let d = m.to_dense();
        for i in 0..n {
            for j in 0..n {
                let w = want.get(&(i.max(j), i.min(j))).copied().unwrap_or(0.0);
                prop_assert_eq!(d[(i, j)].to_bits(), w.to_bits());
            }
        }
    }
}
