//! Mutated configurations against the `flowmbd-belt` binary (issue 35, item 6): every study's
//! `--print-config`, changed one value at a time (`flowmbd_cli::mutation`: numbers to 0, −1,
//! NaN, ±inf, huge, tiny; strings, arrays, dropped keys), must give exit 0 or a one-line
//! error, never a panic, an abort or an unbounded run. A few sampled mutations per study are
//! validated in every `cargo test`; the `#[ignore]`d test also runs the studies under a time
//! and memory limit.

use flowmbd_cli::mutation::{Mode, Mutation, judge, mutations, run_case};
use flowmbd_cli::testing::{fresh_dir, run_binary};
use proptest::prelude::*;
use std::time::Duration;

const EXE: &str = env!("CARGO_BIN_EXE_flowmbd-belt");

/// The studies of the app.
const STUDIES: &[&str] = &["speed-loss", "demo", "ancf", "plate", "fead", "wave"];

/// The mutations of `study`'s default configuration.
fn study_mutations(study: &str) -> Vec<Mutation> {
    let (code, text, err) = run_binary(EXE, &[study, "--print-config"]);
    assert_eq!(code, 0, "{study} --print-config: {err}");
    let m = mutations(&text);
    assert!(!m.is_empty(), "{study}: no mutations of\n{text}");
    m
}

/// What breaks the conventions among the mutations `pick` of every study, in `mode`.
fn findings(pick: &[prop::sample::Index], mode: Mode, tag: &str) -> Vec<String> {
    let mut out = Vec::new();
    for study in STUDIES {
        let all = study_mutations(study);
        for (k, p) in pick.iter().enumerate() {
            let m = &all[p.index(all.len())];
            let dir = fresh_dir(tag, &format!("{study}-{k}"));
            let o = run_case(EXE, study, &m.text, &dir, mode);
            if let Err(e) = judge(&o) {
                out.push(format!("{study} [{}]: {e}", m.what));
            }
            let _ = std::fs::remove_dir_all(&dir);
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2, ..ProptestConfig::default() })]

    // the app conventions (exit 0, or 1/2 with one line; no panic) on sampled mutations,
    // validated through --print-config
    #[test]
    fn mutated_configs_are_accepted_or_refused_in_one_line(
        pick in prop::collection::vec(any::<prop::sample::Index>(), 4)
    ) {
        let f = findings(&pick, Mode::Validate, "belt-mut");
        prop_assert!(f.is_empty(), "{}", f.join("\n"));
    }
}

// the long version: every mutation validated, a sample of them run under the limits
#[test]
#[ignore = "long: runs the studies on mutated configurations (minutes)"]
fn mutated_configs_run_within_bounds() {
    let mut report = Vec::new();
    for study in STUDIES {
        let all = study_mutations(study);
        for (i, m) in all.iter().enumerate() {
            let dir = fresh_dir("belt-mut-long", &format!("{study}-{i}"));
            let v = run_case(EXE, study, &m.text, &dir, Mode::Validate);
            if let Err(e) = judge(&v) {
                report.push(format!("{study} [{}] (validate): {e}", m.what));
            } else if v.code == Some(0) && i % 5 == 0 {
                let o = run_case(
                    EXE,
                    study,
                    &m.text,
                    &dir,
                    Mode::Run {
                        timeout: Duration::from_secs(30),
                    },
                );
                if let Err(e) = judge(&o) {
                    report.push(format!("{study} [{}] (run): {e}", m.what));
                }
            }
            let _ = std::fs::remove_dir_all(&dir);
        }
    }
    assert!(
        report.is_empty(),
        "{} findings:\n{}",
        report.len(),
        report.join("\n")
    );
}
