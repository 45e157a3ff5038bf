//! One validation shape for every configuration and model description in the workspace.
//!
//! A configuration struct implements [`Validate`]; its `validate` returns the first offending
//! field as an [`InvalidField`]: the dotted field path (`rig.impact.substeps`,
//! `pulleys[1].radius`) and the reason. Nested structs validate themselves and the parent
//! prefixes their path with [`InvalidField::within`], so the path a user sees always starts at
//! the configuration's root. Every crate's error type converts from [`InvalidField`] (its
//! "invalid input" variant keeps the path as the item), so library callers get exactly the
//! checks and messages that the apps' users get.
//!
//! The [`check`] functions are the shared range checks (finite, positive, non-negative, within
//! bounds, counts); a message says what was expected, with the unit, and what was given.

use thiserror::Error;

/// A rejected field: its dotted path from the configuration root, and why it is rejected.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{field}: {reason}")]
pub struct InvalidField {
    /// Dotted path of the offending field (e.g. `pulleys[1].radius`).
    pub field: String,
    /// What is wrong with it.
    pub reason: String,
}

impl InvalidField {
    /// A new rejection of `field`.
    pub fn new(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            reason: reason.into(),
        }
    }

    /// The same rejection seen from the parent struct: `prefix.field` (an empty `prefix`
    /// leaves the path as it is).
    pub fn within(mut self, prefix: &str) -> Self {
        if !prefix.is_empty() {
            self.field = if self.field.is_empty() {
                prefix.to_string()
            } else {
                format!("{prefix}.{}", self.field)
            };
        }
        self
    }
}

/// Semantic checks of a configuration beyond its types (positive masses, ordered ranges, sizes
/// a run can afford, ...).
pub trait Validate {
    /// `Ok` when every field is acceptable; otherwise the first offending field, with its path
    /// relative to `self`.
    fn validate(&self) -> Result<(), InvalidField>;

    /// [`validate`](Self::validate) with the path prefixed by `prefix` (for nested structs).
    fn validate_within(&self, prefix: &str) -> Result<(), InvalidField> {
        self.validate().map_err(|e| e.within(prefix))
    }
}

/// Deserializes a unit variant of an internally tagged enum as a table with no other keys:
/// `#[serde(deserialize_with = "mbd_core::validate::unit_variant")]` on the variant.
///
/// serde's `deny_unknown_fields` does not reach unit variants of internally tagged enums:
/// without this, `{ kind = "none", torque = 5 }` reads as `None` and the misplaced `torque`
/// is silently dropped (issue 20). With it, any key besides the tag is an "unknown field" error.
pub fn unit_variant<'de, D: serde::Deserializer<'de>>(d: D) -> Result<(), D::Error> {
    /// A table that must be empty.
    #[derive(serde::Deserialize, schemars::JsonSchema)]
    #[serde(deny_unknown_fields)]
    struct NoFields {}
    <NoFields as serde::Deserialize>::deserialize(d).map(|_| ())
}

/// Deserializes `[f64; N]` from an array of exactly `N` numbers:
/// `#[serde(deserialize_with = "mbd_core::validate::exact_array")]`.
///
/// The TOML reader fills a fixed-size array from the first `N` elements and drops the rest,
/// so `center = [0.0, 0.0, 0.5]` read as `[0.0, 0.0]` (issue 35: a pulley centre with three
/// coordinates was accepted); with this, any other length is an "invalid length" error naming
/// the field and the line.
pub fn exact_array<'de, D: serde::Deserializer<'de>, const N: usize>(
    d: D,
) -> Result<[f64; N], D::Error> {
    let v = <Vec<f64> as serde::Deserialize>::deserialize(d)?;
    let n = v.len();
    v.try_into().map_err(|_| {
        <D::Error as serde::de::Error>::invalid_length(
            n,
            &format!("an array of exactly {N} numbers").as_str(),
        )
    })
}

/// [`exact_array`] for an optional field (with `#[serde(default)]`).
pub fn exact_array_opt<'de, D: serde::Deserializer<'de>, const N: usize>(
    d: D,
) -> Result<Option<[f64; N]>, D::Error> {
    exact_array(d).map(Some)
}

/// [`exact_array`] for an optional list of pairs, such as a schedule's `knots = [[t, v], ...]`
/// (with `#[serde(default)]`): every element an array of exactly two numbers.
pub fn exact_pairs_opt<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<Option<Vec<(f64, f64)>>, D::Error> {
    let v = <Vec<Vec<f64>> as serde::Deserialize>::deserialize(d)?;
    v.into_iter()
        .map(|p| match p[..] {
            [a, b] => Ok((a, b)),
            _ => Err(<D::Error as serde::de::Error>::invalid_length(
                p.len(),
                &"pairs [x, y] of exactly two numbers",
            )),
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// The documented ceilings on sizes and run lengths taken from input, and the one switch that
/// raises them (issue 20, item 2).
///
/// Every size a run allocates from (nodes, elements, divisions, time steps, recorded samples,
/// output frames) is checked against a documented constant of its crate before anything is
/// allocated or run (`flowing::string_study::MAX_STRING_NODES`, `MAX_RIG_STEPS`, ...), so
/// absurd input (`--nodes 1e9`, `record_time = 1e300`) is a one-line error naming the field
/// instead of an allocation abort or a run that never ends. A user who really wants a larger
/// model raises every ceiling [`LARGE_FACTOR`](limits::LARGE_FACTOR)-fold: `--allow-large` on any `flowmbd-*`
/// study, or [`set_allow_large`](limits::set_allow_large) from library code. The raised ceilings are still finite, so
/// sizes such as `1e300` s stay refused (no overflow of a count, no endless run).
pub mod limits {
    use std::sync::atomic::{AtomicBool, Ordering};

    static ALLOW_LARGE: AtomicBool = AtomicBool::new(false);

    /// How much [`set_allow_large`] raises every ceiling.
    pub const LARGE_FACTOR: f64 = 1000.0;

    /// Raise (`true`) or restore (`false`) every ceiling, process-wide (the apps'
    /// `--allow-large`; set it before validating a configuration).
    pub fn set_allow_large(yes: bool) {
        ALLOW_LARGE.store(yes, Ordering::Relaxed);
    }

    /// Whether the ceilings are raised.
    pub fn large_allowed() -> bool {
        ALLOW_LARGE.load(Ordering::Relaxed)
    }

    /// The ceiling in force for a documented ceiling `default` (a run length or sample count):
    /// `default`, or [`LARGE_FACTOR`] × `default` when raised.
    pub fn ceiling(default: f64) -> f64 {
        if large_allowed() {
            default * LARGE_FACTOR
        } else {
            default
        }
    }

    /// [`ceiling`] for a count (nodes, elements, divisions).
    pub fn ceiling_count(default: usize) -> usize {
        if large_allowed() {
            default.saturating_mul(LARGE_FACTOR as usize)
        } else {
            default
        }
    }

    /// Bytes of memory the machine has available now (Linux: `MemAvailable` of
    /// `/proc/meminfo`), `None` where it cannot be told.
    pub fn available_memory() -> Option<f64> {
        let text = std::fs::read_to_string("/proc/meminfo").ok()?;
        let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
        let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kib * 1024.0)
    }

    /// `Ok` when an allocation of about `bytes` (estimated from input before allocating)
    /// fits in the memory available now ([`available_memory`]); `--allow-large` raises the
    /// ceilings but never removes this check (issue 35: a Matrix Market header of 3e9 × 3e9
    /// with `--allow-large` grew until the machine ran out of memory). Where the available
    /// memory cannot be told, only the ceilings apply.
    pub fn check_memory(what: &str, bytes: f64) -> Result<(), super::InvalidField> {
        match available_memory() {
            Some(avail) if bytes > avail => Err(super::InvalidField::new(
                what,
                format!(
                    "needs about {} of memory, more than the {} this machine has available",
                    show_bytes(bytes),
                    show_bytes(avail)
                ),
            )),
            _ => Ok(()),
        }
    }

    /// `bytes` in GB or MB for messages.
    fn show_bytes(bytes: f64) -> String {
        if bytes >= 1e9 {
            format!("{:.1} GB", bytes / 1e9)
        } else {
            format!("{:.1} MB", bytes / 1e6)
        }
    }

    /// What a refusal at a ceiling ends with: how to raise it (empty once raised).
    pub fn raise_hint() -> &'static str {
        if large_allowed() {
            ""
        } else {
            " (a documented ceiling: --allow-large raises it 1000-fold)"
        }
    }
}

/// Text taken from input (a token of a file, a key, a path) made safe to quote in a one-line
/// message (issue 35, item 7): control characters (newlines, tabs, ESC of terminal escape
/// sequences, DEL, C1 controls) and Unicode format characters (bidirectional overrides) are
/// written as Rust escapes (`\n`, `\u{1b}`), and text longer than [`ESCAPE_MAX_CHARS`]
/// characters is cut with `…`. Printable text, including non-ASCII letters, is unchanged.
/// Every error message that quotes input goes through this one function.
pub fn escape(text: &str) -> String {
    escape_chars(text, Some(ESCAPE_MAX_CHARS))
}

/// A whole message made safe for one terminal line: as [`escape`], without the cut, and
/// with line breaks written as spaces (the apps' last line on stderr).
pub fn escape_message(text: &str) -> String {
    escape_chars(&text.replace(['\n', '\r'], " "), None)
}

fn escape_chars(text: &str, max: Option<usize>) -> String {
    let mut out = String::with_capacity(text.len().min(4096));
    for (i, c) in text.chars().enumerate() {
        if Some(i) == max {
            out.push('…');
            break;
        }
        let unsafe_char = c.is_control()
            || matches!(
                c,
                '\u{200b}'..='\u{200f}'
                    | '\u{202a}'..='\u{202e}'
                    | '\u{2066}'..='\u{2069}'
                    | '\u{feff}'
            );
        if unsafe_char {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// How many characters of an input text [`escape`] keeps.
pub const ESCAPE_MAX_CHARS: usize = 200;

/// Plausibility of results (issue 35, item 5): a non-finite or physically impossible result
/// (a negative frequency, an extension longer than the body) is reported, never passed on as
/// `null` or as a number.
///
/// A study collects its checks in a [`plausible::Checks`] and turns the first failure into
/// an error ([`plausible::Implausible`], which names the quantity and why); the apps write
/// the summary so far with `"complete": false` and exit 1 (`flowmbd_cli::StudyError::implausible`).
pub mod plausible {
    use super::check::show;
    use thiserror::Error;

    /// A result that cannot be right: the quantity and why.
    #[derive(Debug, Error, Clone, PartialEq)]
    #[error("implausible result {quantity}: {reason}")]
    pub struct Implausible {
        /// Name of the result (a summary field, `frequencies_hz[3]`).
        pub quantity: String,
        /// What is wrong with it.
        pub reason: String,
    }

    /// The checks of one result set; the first failure is kept.
    #[derive(Debug, Default)]
    pub struct Checks {
        first: Option<Implausible>,
    }

    impl Checks {
        /// No checks yet.
        pub fn new() -> Self {
            Self::default()
        }

        fn fail(&mut self, quantity: &str, reason: String) {
            if self.first.is_none() {
                self.first = Some(Implausible {
                    quantity: quantity.to_string(),
                    reason,
                });
            }
        }

        /// `value` is finite (not NaN, not infinite).
        pub fn finite(&mut self, quantity: &str, value: f64) -> &mut Self {
            if !value.is_finite() {
                let what = if value.is_nan() {
                    "is not a number (NaN)".to_string()
                } else {
                    format!("is {}", show(value))
                };
                self.fail(quantity, what);
            }
            self
        }

        /// Every value of `values` is finite (`quantity[i]` names the first that is not).
        pub fn all_finite(&mut self, quantity: &str, values: &[f64]) -> &mut Self {
            for (i, v) in values.iter().enumerate() {
                self.finite(&format!("{quantity}[{i}]"), *v);
            }
            self
        }

        /// `value` is finite and `≥ 0` (`what` says why it must be, e.g. "a frequency").
        pub fn non_negative(&mut self, quantity: &str, value: f64, what: &str) -> &mut Self {
            self.finite(quantity, value);
            if value < 0.0 {
                self.fail(
                    quantity,
                    format!("is {} but {what} cannot be negative", show(value)),
                );
            }
            self
        }

        /// Every value of `values` is finite and `≥ 0`.
        pub fn all_non_negative(
            &mut self, quantity: &str, values: &[f64], what: &str,
        ) -> &mut Self {
            for (i, v) in values.iter().enumerate() {
                self.non_negative(&format!("{quantity}[{i}]"), *v, what);
            }
            self
        }

        /// `|value| ≤ bound` (`why` names the bound, e.g. "the beam's length 8 m").
        pub fn magnitude_at_most(
            &mut self, quantity: &str, value: f64, bound: f64, why: &str,
        ) -> &mut Self {
            self.finite(quantity, value);
            if value.abs() > bound {
                self.fail(
                    quantity,
                    format!("|{}| exceeds {why} ({})", show(value), show(bound)),
                );
            }
            self
        }

        /// A condition stated by the caller (`reason` is used when `ok` is false).
        pub fn require(&mut self, quantity: &str, ok: bool, reason: &str) -> &mut Self {
            if !ok {
                self.fail(quantity, reason.to_string());
            }
            self
        }

        /// `Ok` when every check passed, else the first failure.
        pub fn result(&self) -> Result<(), Implausible> {
            match &self.first {
                None => Ok(()),
                Some(e) => Err(e.clone()),
            }
        }
    }
}

/// The shared range checks. Each returns the [`InvalidField`] for `field` when `value` fails.
///
/// Messages say what was expected and what was given; a NaN is called "not a number" (never
/// "negative" or "not positive"), and very large or small values are written with an exponent
/// (`1e300`, not 301 digits).
pub mod check {
    use super::InvalidField;

    /// `value` written for a message: `NaN (not a number)`, `inf`, an exponent form for
    /// magnitudes at or above 10⁶ or below 10⁻⁴, else the shortest decimal form.
    pub fn show(value: f64) -> String {
        if value.is_nan() {
            "NaN (not a number)".to_string()
        } else if value.is_infinite() || value == 0.0 {
            format!("{value}")
        } else if value.abs() >= 1e6 || value.abs() < 1e-4 {
            format!("{value:e}")
        } else {
            format!("{value}")
        }
    }

    /// The rejection of `value` for `field`, which was expected to be `expected`: a NaN is
    /// reported as not a number, anything else as "must be `expected`, got `value`".
    pub fn reject(field: &str, expected: &str, value: f64) -> InvalidField {
        if value.is_nan() {
            InvalidField::new(field, format!("is not a number (NaN); expected {expected}"))
        } else {
            InvalidField::new(field, format!("must be {expected}, got {}", show(value)))
        }
    }

    /// `value` is finite.
    pub fn finite(field: &str, value: f64) -> Result<(), InvalidField> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(reject(field, "finite", value))
        }
    }

    /// `value` is finite and `> 0` (`unit` names the unit in the message, e.g. `"m"`).
    pub fn positive(field: &str, value: f64, unit: &str) -> Result<(), InvalidField> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(reject(
                field,
                &format!("finite and > 0{}", with_unit(unit)),
                value,
            ))
        }
    }

    /// `value` is finite and `≥ 0`.
    pub fn non_negative(field: &str, value: f64, unit: &str) -> Result<(), InvalidField> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(reject(
                field,
                &format!("finite and >= 0{}", with_unit(unit)),
                value,
            ))
        }
    }

    /// `lo ≤ value ≤ hi` (and finite).
    pub fn within(
        field: &str, value: f64, lo: f64, hi: f64, unit: &str,
    ) -> Result<(), InvalidField> {
        if value.is_finite() && (lo..=hi).contains(&value) {
            Ok(())
        } else {
            Err(reject(
                field,
                &format!("in [{}, {}]{}", show(lo), show(hi), with_unit(unit)),
                value,
            ))
        }
    }

    /// A count `lo ≤ n ≤ hi` (sizes taken from input are bounded before anything is allocated).
    pub fn count(field: &str, n: usize, lo: usize, hi: usize) -> Result<(), InvalidField> {
        if (lo..=hi).contains(&n) {
            Ok(())
        } else {
            Err(InvalidField::new(
                field,
                format!("must lie in [{lo}, {hi}], got {n}"),
            ))
        }
    }

    /// `Ok` when `path` is a readable regular file; otherwise the [`InvalidField`] for `field`
    /// saying whether the path does not exist, is a directory, or cannot be inspected (input
    /// files named in a configuration: the apps and the Python package check them alike).
    pub fn input_file(field: &str, path: &std::path::Path) -> Result<(), InvalidField> {
        let shown = path.display();
        match std::fs::metadata(path) {
            Ok(m) if m.is_dir() => Err(InvalidField::new(
                field,
                format!("`{shown}` is a directory, expected a file"),
            )),
            Ok(m) if m.is_file() => match std::fs::File::open(path) {
                Ok(_) => Ok(()),
                Err(e) => Err(InvalidField::new(
                    field,
                    format!("cannot read `{shown}`: {e}"),
                )),
            },
            Ok(_) => Err(InvalidField::new(
                field,
                format!("`{shown}` is not a regular file"),
            )),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Err(InvalidField::new(
                field,
                format!("file `{shown}` does not exist"),
            )),
            Err(e) => Err(InvalidField::new(
                field,
                format!("cannot read `{shown}`: {e}"),
            )),
        }
    }

    /// A size from input `lo ≤ n ≤` the ceiling in force for the documented ceiling `max`
    /// ([`super::limits::ceiling_count`]); the refusal says how to raise the ceiling.
    pub fn size(field: &str, n: usize, lo: usize, max: usize) -> Result<(), InvalidField> {
        let hi = super::limits::ceiling_count(max);
        if n < lo {
            return count(field, n, lo, hi);
        }
        if n > hi {
            return Err(InvalidField::new(
                field,
                format!(
                    "must lie in [{lo}, {hi}], got {n}{}",
                    super::limits::raise_hint()
                ),
            ));
        }
        Ok(())
    }

    /// A time step `h` \[s\] (field `h_field`) no longer than the run `run` \[s\] (field
    /// `run_field`) it divides (issue 35: `h = 30` s with `t_end = 20` s ran one step past the
    /// end). Both are expected positive and finite (checked before).
    pub fn step_fits(h_field: &str, h: f64, run_field: &str, run: f64) -> Result<(), InvalidField> {
        if h <= run {
            Ok(())
        } else {
            Err(InvalidField::new(
                h_field,
                format!(
                    "a step of {} s is longer than the run ({run_field} = {} s)",
                    show(h),
                    show(run)
                ),
            ))
        }
    }

    fn with_unit(unit: &str) -> String {
        if unit.is_empty() {
            String::new()
        } else {
            format!(" {unit}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Inner {
        radius: f64,
    }
    impl Validate for Inner {
        fn validate(&self) -> Result<(), InvalidField> {
            check::positive("radius", self.radius, "m")
        }
    }
    struct Outer {
        pulleys: Vec<Inner>,
    }
    impl Validate for Outer {
        fn validate(&self) -> Result<(), InvalidField> {
            for (i, p) in self.pulleys.iter().enumerate() {
                p.validate_within(&format!("pulleys[{i}]"))?;
            }
            Ok(())
        }
    }

    // invariant: the path a user sees starts at the root and ends at the field
    #[test]
    fn nested_paths_start_at_the_root() {
        let o = Outer {
            pulleys: vec![Inner { radius: 0.05 }, Inner { radius: f64::NAN }],
        };
        let e = o.validate().unwrap_err();
        assert_eq!(e.field, "pulleys[1].radius");
        assert_eq!(
            e.to_string(),
            "pulleys[1].radius: is not a number (NaN); expected finite and > 0 m"
        );
        assert_eq!(e.clone().within("drive").field, "drive.pulleys[1].radius");
        assert!(
            Outer {
                pulleys: vec![Inner { radius: 1.0 }]
            }
            .validate()
            .is_ok()
        );
    }

    #[test]
    fn range_checks_reject_non_finite_and_out_of_range_values() {
        assert!(check::non_negative("x", 0.0, "").is_ok());
        assert!(check::non_negative("x", -1e-300, "").is_err());
        assert!(check::within("rho", 1.0, 0.0, 1.0, "").is_ok());
        assert!(check::within("rho", f64::INFINITY, 0.0, f64::INFINITY, "").is_err());
        assert_eq!(
            check::count("substeps", 1_000_000_000, 1, 1000)
                .unwrap_err()
                .reason,
            "must lie in [1, 1000], got 1000000000"
        );
        assert!(check::finite("t", f64::NEG_INFINITY).is_err());
    }

    // issue 35 item 7: a terminal escape sequence in a file must not reach the terminal
    #[test]
    fn escape_neutralises_control_characters_and_cuts_long_text() {
        assert_eq!(escape("1.0e\u{1b}[31mred"), "1.0e\\u{1b}[31mred");
        assert_eq!(escape("a\nb\tc"), "a\\nb\\tc");
        assert_eq!(escape("Kerkkänen"), "Kerkkänen");
        assert_eq!(escape("x\u{202e}y"), "x\\u{202e}y");
        let long = "x".repeat(1000);
        assert_eq!(escape(&long).chars().count(), ESCAPE_MAX_CHARS + 1);
    }

    // issue 35 item 2: an allocation larger than the machine is refused even with the
    // ceilings raised (definition: more than any machine's memory)
    #[test]
    fn allocations_beyond_the_machine_are_refused() {
        limits::set_allow_large(true);
        let e = limits::check_memory("matrix", 1e30);
        limits::set_allow_large(false);
        if limits::available_memory().is_some() {
            assert!(e.unwrap_err().reason.contains("available"));
        }
        assert!(limits::check_memory("x", 1.0).is_ok());
    }

    // issue 35 item 5: the first failing check is reported with its quantity
    #[test]
    fn plausibility_checks_report_the_first_failure() {
        let mut c = plausible::Checks::new();
        c.finite("a", 1.0).non_negative("f_hz", 3.0, "a frequency");
        assert!(c.result().is_ok());
        c.all_non_negative("exact_hz", &[1.0, -9.34], "a frequency")
            .finite("b", f64::NAN);
        let e = c.result().unwrap_err();
        assert_eq!(e.quantity, "exact_hz[1]");
        assert!(e.reason.contains("-9.34"), "{e}");
        let mut c = plausible::Checks::new();
        c.magnitude_at_most("extension_m", -8.0, 8.0, "the length")
            .finite("w", f64::INFINITY);
        assert_eq!(c.result().unwrap_err().quantity, "w");
    }

    // issue 20: `lead = nan` said "NaN s is negative"; 1e300 was printed with 301 digits
    #[test]
    fn nan_is_called_not_a_number_and_huge_values_use_an_exponent() {
        let e = check::non_negative("impact.lead", f64::NAN, "m").unwrap_err();
        assert_eq!(
            e.to_string(),
            "impact.lead: is not a number (NaN); expected finite and >= 0 m"
        );
        assert!(!e.reason.contains("negative"), "{e}");
        let e = check::within("record_time", 1e300, 0.0, 10.0, "s").unwrap_err();
        assert_eq!(e.reason, "must be in [0, 10] s, got 1e300");
        assert_eq!(check::show(-2.5e-7), "-2.5e-7");
        assert_eq!(check::show(0.85), "0.85");
        assert_eq!(check::show(f64::INFINITY), "inf");
    }
}
