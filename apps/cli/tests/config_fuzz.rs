//! Property tests of the TOML configuration reader (issue #20): arbitrary text and mutated
//! real configurations (the belt drive, the tire rig, the generated tire and the library
//! study configurations shared with Python: ANCF drive, speed loss, string modes; each
//! `Default` is the seed's case) give a configuration or a one-line error with a line inside
//! the file, never a panic; what parses is validated without panicking either. These are the
//! bodies of the cargo-fuzz target `fuzz/fuzz_targets/toml_config.rs` run as ordinary tests,
//! a few thousand cases per run.

use drives::ancf_study::AncfStudyConfig;
use drives::fead::FeadConfig;
use drives::speed_loss_study::SpeedLossStudyConfig;
use fe_model::generate::TireConfig;
use flowing::string_study::ModesConfig;
use flowmbd_cases::ancf_dynamics::{PendulumCase, SpinningCase};
use flowmbd_cases::lin::beam::LinBeamConfig;
use flowmbd_cases::lin::slab_sim::SlabSimConfig;
use flowmbd_cli::config::{parse_config, to_toml};
use flowmbd_cli::{CliError, PartialRules, Validate};
use proptest::prelude::*;
use std::path::Path;
use tire::RigConfig;

/// Parse and validate `text` as `C`; errors must be one line and point into the text.
fn check<C: serde::de::DeserializeOwned + serde::Serialize + Default + Validate + PartialRules>(
    text: &str,
) -> Result<(), TestCaseError> {
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

/// The default rig with a prescribed wheel-centre motion (`[wheel.centre_motion]`, every
/// column given) on the flat road it requires: the series' keys are mutated too.
fn rig_with_centre_motion() -> RigConfig {
    let mut rig = RigConfig::default();
    rig.ground.kind = tire::GroundKind::Road;
    rig.ground.cleat = false;
    let col = |a: f64, b: f64| Some(vec![a, b]);
    rig.wheel.centre_motion = Some(tire::motion::CentreMotion {
        time: vec![0.0, 0.1],
        height: col(0.49, 0.488),
        velocity_x: col(16.0, 16.5),
        velocity_y: col(0.0, 0.1),
        velocity_z: col(0.0, 0.0),
        yaw: col(0.0, 0.01),
        camber: col(0.0, 0.01),
        spin_rate: col(33.0, 34.0),
        communication_step: Some(1e-3),
    });
    rig
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
        check::<FeadConfig>(&text)?;
    }

    #[test]
    fn mutated_defaults_never_panic(pick in any::<prop::sample::Index>(), value in odd_value()) {
        check::<RigConfig>(&mutate(&to_toml(&RigConfig::default()), pick, &value))?;
        check::<RigConfig>(&mutate(&to_toml(&rig_with_centre_motion()), pick, &value))?;
        check::<FeadConfig>(&mutate(&to_toml(&FeadConfig::default()), pick, &value))?;
        check::<TireConfig>(&mutate(&to_toml(&TireConfig::default()), pick, &value))?;
        check::<AncfStudyConfig>(&mutate(&to_toml(&AncfStudyConfig::default()), pick, &value))?;
        check::<SpeedLossStudyConfig>(
            &mutate(&to_toml(&SpeedLossStudyConfig::default()), pick, &value),
        )?;
        check::<ModesConfig>(&mutate(&to_toml(&ModesConfig::default()), pick, &value))?;
        // issue 35: the beam and reduction cases validated in their library crate
        check::<PendulumCase>(&mutate(&to_toml(&PendulumCase::default()), pick, &value))?;
        check::<SpinningCase>(&mutate(&to_toml(&SpinningCase::default()), pick, &value))?;
        check::<LinBeamConfig>(&mutate(&to_toml(&LinBeamConfig::default()), pick, &value))?;
        check::<SlabSimConfig>(&mutate(&to_toml(&SlabSimConfig::default()), pick, &value))?;
    }
}

// Issue 20: every table of the library configurations rejects an unknown key (their defaults
// and, for the ANCF drive, the non-default torque and speed profiles); definition: each table
// is `deny_unknown_fields`, which serde does not apply to unit variants of internally tagged
// enums nor to structs in newtype variants unless asked
#[test]
fn library_configurations_reject_unknown_keys_everywhere() {
    use flowmbd_cli::config::tables_accepting_unknown_keys;
    assert_eq!(
        tables_accepting_unknown_keys(&RigConfig::default()),
        Vec::<String>::new()
    );
    assert_eq!(
        tables_accepting_unknown_keys(&rig_with_centre_motion()),
        Vec::<String>::new()
    );
    assert_eq!(
        tables_accepting_unknown_keys(&FeadConfig::default()),
        Vec::<String>::new()
    );
    assert_eq!(
        tables_accepting_unknown_keys(&TireConfig::default()),
        Vec::<String>::new()
    );
    assert_eq!(
        tables_accepting_unknown_keys(&AncfStudyConfig::default()),
        Vec::<String>::new()
    );
    assert_eq!(
        tables_accepting_unknown_keys(&SpeedLossStudyConfig::default()),
        Vec::<String>::new()
    );
    assert_eq!(
        tables_accepting_unknown_keys(&ModesConfig::default()),
        Vec::<String>::new()
    );
    // the other variants of the tire's normal law and friction law
    let mut rig = RigConfig::default();
    rig.rolling.normal = tire::NormalContact::Penalty { stiffness: 1e7 };
    rig.rolling.friction_law = tire::TireFriction::Law(contact::FrictionSpec::Frictionless);
    assert_eq!(tables_accepting_unknown_keys(&rig), Vec::<String>::new());
}
