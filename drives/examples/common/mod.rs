//! What the diagnostic examples share: their `key=value` command-line arguments.

use std::collections::HashMap;

/// The numeric `key=value` arguments of the command line (others ignored), read as
/// `arg("key", default)`.
pub fn numeric_args() -> impl Fn(&str, f64) -> f64 {
    let args: HashMap<String, f64> = std::env::args()
        .skip(1)
        .filter_map(|a| {
            let (k, v) = a.split_once('=')?;
            Some((k.to_string(), v.parse().ok()?))
        })
        .collect();
    move |k, d| args.get(k).copied().unwrap_or(d)
}
