//! Mutated configurations against the `flowmbd-tire` binary (issue 35, item 6): every study's
//! `--print-config`, changed one value at a time (`flowmbd_cli::mutation`: numbers to 0, −1,
//! NaN, ±inf, huge, tiny; strings, arrays, dropped keys), must give exit 0 or a one-line
//! error, never a panic, an abort or an unbounded run. A few sampled mutations per study are
//! validated in every `cargo test`; the `#[ignore]`d test also runs the studies under a time
//! and memory limit.

use flowmbd_cli::mutation::{exhaustive_findings, sampled_findings};
use proptest::prelude::*;
use std::time::Duration;

const EXE: &str = env!("CARGO_BIN_EXE_flowmbd-tire");

/// The studies of the app.
const STUDIES: &[&str] = &[
    "modes",
    "reduce",
    "cleat",
    "sweep",
    "pressure",
    "rotating-modes",
    "dips",
    "steady",
];

proptest! {
    #![proptest_config(ProptestConfig { cases: 2, ..ProptestConfig::default() })]

    // the app conventions (exit 0, or 1/2 with one line; no panic) on sampled mutations,
    // validated through --print-config
    #[test]
    fn mutated_configs_are_accepted_or_refused_in_one_line(
        pick in prop::collection::vec(any::<usize>(), 4)
    ) {
        let f = sampled_findings(EXE, STUDIES, &pick, "tire-mut");
        prop_assert!(f.is_empty(), "{}", f.join("\n"));
    }
}

// the long version: every mutation validated, a sample of them run under the limits
#[test]
#[ignore = "long: runs the studies on mutated configurations (minutes)"]
fn mutated_configs_run_within_bounds() {
    let report = exhaustive_findings(EXE, STUDIES, "tire-mut-long", 5, Duration::from_secs(30));
    assert!(
        report.is_empty(),
        "{} findings:\n{}",
        report.len(),
        report.join("\n")
    );
}
