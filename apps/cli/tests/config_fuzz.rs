//! Property tests of the TOML configuration reader (issue #20): arbitrary text and mutated
//! real configurations (the belt drive and the tire rig, whose `Default` is the seed's case)
//! give a configuration or a one-line error with a line inside the file, never a panic; what
//! parses is validated without panicking either. A few thousand cases per run.

use flowing::belt::BeltDriveConfig;
use flowing::tire::RigConfig;
use flowmbd_cli::config::{parse_config, to_toml};
use flowmbd_cli::{CliError, Validate};
use proptest::prelude::*;
use std::path::Path;

/// Parse and validate `text` as `C`; errors must be one line and point into the text.
fn check<C: serde::de::DeserializeOwned + Validate>(text: &str) -> Result<(), TestCaseError> {
    match parse_config::<C>(text, Path::new("f.toml")) {
        Ok(c) => {
            let _ = c.validate();
        }
        Err(e) => {
            let msg = e.to_string();
            prop_assert!(!msg.contains('\n'), "one line: {msg}");
            if let CliError::ParseConfig { line, .. } = e {
                prop_assert!(line >= 1 && line <= text.lines().count() + 1, "{msg}");
            }
        }
    }
    Ok(())
}

/// A value a user (or a fuzzer) might type.
fn odd_value() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("-inf".to_string()),
        Just("1e300".to_string()),
        Just("-1".to_string()),
        Just("0".to_string()),
        Just("18446744073709551615".to_string()),
        Just("9223372036854775807".to_string()),
        Just("\"é\"".to_string()),
        Just("[]".to_string()),
        Just("{}".to_string()),
        any::<f64>().prop_map(|x| format!("{x:?}")),
        any::<i64>().prop_map(|x| x.to_string()),
        "[ -~é€]{0,8}",
    ]
}

/// The default configuration's TOML with the value of one `key = value` line replaced.
fn mutate(text: &str, pick: prop::sample::Index, value: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let assigns: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].contains(" = "))
        .collect();
    if assigns.is_empty() {
        return text.to_string();
    }
    let i = assigns[pick.index(assigns.len())];
    let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    if let Some((k, _)) = lines[i].split_once(" = ") {
        out[i] = format!("{k} = {value}");
    }
    out.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn arbitrary_text_never_panics(text in "[ -~\\n\\té€]{0,120}") {
        check::<RigConfig>(&text)?;
        check::<BeltDriveConfig>(&text)?;
    }

    #[test]
    fn mutated_defaults_never_panic(pick in any::<prop::sample::Index>(), value in odd_value()) {
        check::<RigConfig>(&mutate(&to_toml(&RigConfig::default()), pick, &value))?;
        check::<BeltDriveConfig>(&mutate(&to_toml(&BeltDriveConfig::default()), pick, &value))?;
    }
}
