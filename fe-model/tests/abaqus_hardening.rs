//! The ABAQUS matrix reader never panics on arbitrary or mutated input (issue #20), and a
//! syntax error names file and line. Sizes: the reader allocates per line read (no header), so
//! memory follows the file's length; node labels and DOF numbers are bounded integers.

use fe_model::FeError;
use fe_model::io::abaqus;
use proptest::prelude::*;

/// Each malformed line is reported at its line (reference: the line we broke).
#[test]
fn syntax_errors_name_file_and_line() {
    for (text, line) in [
        ("1,1,1,1,2.0\n1,1,2\n", 2),
        ("** c\n1,1,1,1,2.0\n1,0,1,1,1\n", 3),
        ("1,1,1,1,nan\n", 1),
        ("18446744073709551616,1,1,1,1\n", 1),
        ("1,4294967296,1,1,1\n", 1),
    ] {
        match abaqus::parse(text, "job_STIF1.mtx") {
            Err(e @ FeError::Matrix { .. }) => {
                assert!(
                    e.to_string().starts_with(&format!("job_STIF1.mtx:{line}:")),
                    "{e}"
                )
            }
            other => panic!("{text:?}: {other:?}"),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Arbitrary text never panics, neither parsing nor assembling what parsed.
    #[test]
    fn random_text_never_panics(text in "[0-9,.eE+\\-* \\n]{0,120}") {
        if let Ok(e) = abaqus::parse(&text, "f") {
            let _ = abaqus::assemble(&[&e]);
        }
    }

    /// One triangle written as ABAQUS entries reads back mirrored (second formulation: the
    /// generated entries).
    #[test]
    fn one_triangle_round_trip(raw in proptest::collection::vec((1u64..5, 1u32..4, 1u64..5, 1u32..4, -1e3f64..1e3), 1..12)) {
        let mut want = std::collections::BTreeMap::new();
        for (n1, d1, n2, d2, v) in raw {
            let (a, b) = ((n1, d1).max((n2, d2)), (n1, d1).min((n2, d2)));
            want.insert((a, b), v);
        }
        let text: String = want.iter().map(|(&((n1, d1), (n2, d2)), v)| format!("{n1},{d1},{n2},{d2},{v:?}\n")).collect();
        let e = abaqus::parse(&text, "f").unwrap();
        let (map, mats) = abaqus::assemble(&[&e]).unwrap();
        let d = mats[0].to_dense();
        for (&((n1, d1), (n2, d2)), &v) in &want {
            let (i, j) = (map.index(n1, d1).unwrap(), map.index(n2, d2).unwrap());
            prop_assert_eq!(d[(i, j)], v);
            prop_assert_eq!(d[(j, i)], v);
        }
    }
}
