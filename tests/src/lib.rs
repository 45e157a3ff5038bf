//! # flowmbd-validation
//!
//! Cross-crate validation of flowmbd against the seeds' tables, analytical solutions and
//! invariants. The tests live in `tests/tests/*.rs`; this library holds shared reference data.
