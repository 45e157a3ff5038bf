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

/// The shared range checks. Each returns the [`InvalidField`] for `field` when `value` fails.
pub mod check {
    use super::InvalidField;

    /// `value` is finite.
    pub fn finite(field: &str, value: f64) -> Result<(), InvalidField> {
        if value.is_finite() {
            Ok(())
        } else {
            Err(InvalidField::new(
                field,
                format!("must be finite, got {value}"),
            ))
        }
    }

    /// `value` is finite and `> 0` (`unit` names the unit in the message, e.g. `"m"`).
    pub fn positive(field: &str, value: f64, unit: &str) -> Result<(), InvalidField> {
        if value.is_finite() && value > 0.0 {
            Ok(())
        } else {
            Err(InvalidField::new(
                field,
                format!("must be finite and > 0{}, got {value}", with_unit(unit)),
            ))
        }
    }

    /// `value` is finite and `≥ 0`.
    pub fn non_negative(field: &str, value: f64, unit: &str) -> Result<(), InvalidField> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(InvalidField::new(
                field,
                format!("must be finite and >= 0{}, got {value}", with_unit(unit)),
            ))
        }
    }

    /// `lo ≤ value ≤ hi` (and finite).
    pub fn within(
        field: &str,
        value: f64,
        lo: f64,
        hi: f64,
        unit: &str,
    ) -> Result<(), InvalidField> {
        if value.is_finite() && (lo..=hi).contains(&value) {
            Ok(())
        } else {
            Err(InvalidField::new(
                field,
                format!("must lie in [{lo}, {hi}]{}, got {value}", with_unit(unit)),
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
            "pulleys[1].radius: must be finite and > 0 m, got NaN"
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
}
