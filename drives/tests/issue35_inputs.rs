//! Issue 35: the library checks of input sizes, run lengths and coordinates (shared by the
//! apps and the Python package), before anything is allocated or run.

use drives::SpeedLossStudyConfig;
use drives::ancf_study::AncfStudyConfig;
use mbd_core::validate::Validate;

// issue 35: 2^63 - 1 ANCF belt elements overflowed a Vec's capacity, 2^32 + 1 asked for
// 860 GB; ancf::belt_drive MAX_ELEMENTS = 2000 (×1000 with --allow-large), MAX_GAUSS_POINTS = 20
#[test]
fn ancf_drive_sizes_have_ceilings() {
    for n in [
        usize::MAX,
        9_223_372_036_854_775_807,
        4_294_967_297,
        100_000,
        2001,
        2,
    ] {
        let mut c = AncfStudyConfig::default();
        c.drive.belt.elements = n;
        let e = c.validate().unwrap_err();
        assert!(e.field.contains("belt.elements"), "{n}: {e}");
    }
    let mut c = AncfStudyConfig::default();
    c.drive.belt.elements = 2000;
    c.drive.belt.gauss_points = 20;
    assert!(c.validate().is_ok());
    for g in [0, 21, 4_294_967_297] {
        let mut c = AncfStudyConfig::default();
        c.drive.belt.gauss_points = g;
        let e = c.validate().unwrap_err();
        assert!(e.field.contains("belt.gauss_points"), "{g}: {e}");
    }
}

// issue 35: `wave.t_end = 1e9` ran without end; flowing::belt::wave::MAX_WAVE_STEPS = 1e7
// steps and MAX_WAVE_SAMPLES = 1e5 samples
#[test]
fn wave_run_length_and_samples_have_ceilings() {
    use flowing::belt::wave::{MAX_WAVE_SAMPLES, MAX_WAVE_STEPS, WaveConfig};
    let ok = WaveConfig::default();
    assert!(ok.validate().is_ok());
    let long = WaveConfig { t_end: 1e9, ..ok };
    assert_eq!(long.validate().unwrap_err().field, "t_end");
    // exactly at the ceiling is accepted
    let at = WaveConfig {
        t_end: MAX_WAVE_STEPS * ok.step,
        samples: 1000,
        ..ok
    };
    assert!(at.validate().is_ok(), "{:?}", at.validate());
    let many = WaveConfig {
        samples: MAX_WAVE_SAMPLES + 1,
        step: 1e-7,
        ..ok
    };
    assert_eq!(many.validate().unwrap_err().field, "samples");
}

// issue 35: `--omega 1e300` ran (and failed writing a file named by the speed); the belt speed
// ω R of the driver must stay below the critical speed c = √(T0/ρA) of the mounted belt
// (Wickert and Mote): Table 6-1's c = 56.8 m/s on the 50 mm driver is 1136.5 rad/s
#[test]
fn driver_speed_below_the_critical_speed() {
    let c = SpeedLossStudyConfig {
        omegas: vec![62.8, 1e300],
        ..Default::default()
    };
    let e = c.validate().unwrap_err();
    assert_eq!(e.field, "omegas[1]");
    assert!(e.reason.contains("critical speed"), "{e}");
    let near = SpeedLossStudyConfig {
        omegas: vec![1100.0],
        ..Default::default()
    };
    assert!(near.validate().is_ok(), "{:?}", near.validate());
    let above = SpeedLossStudyConfig {
        omegas: vec![1140.0],
        ..Default::default()
    };
    assert_eq!(above.validate().unwrap_err().field, "omegas[0]");
}

// issue 35: the TOML reader fills `[f64; 2]` from the first two numbers and drops the rest, so
// a pulley centre with three coordinates was accepted (mbd_core::validate::exact_array)
#[test]
fn coordinates_must_have_exactly_two_numbers() {
    let pulley = |center: &str| {
        format!(
            "name = \"p\"\ncenter = {center}\nradius = 0.1\n\
             motion = {{ kind = \"idler\", inertia = 0.001, damping = 0.0 }}\n"
        )
    };
    assert!(toml::from_str::<belt::Pulley>(&pulley("[0.0, 0.5]")).is_ok());
    for bad in ["[0.0, 0.5, 1.0]", "[0.0]", "[]"] {
        let e = toml::from_str::<belt::Pulley>(&pulley(bad)).unwrap_err();
        assert!(e.to_string().contains("exactly 2 numbers"), "{bad}: {e}");
    }
    let knots = "kind = \"schedule\"\nknots = [[0.0, 0.0, 9.0], [1.0, 2.0]]\n";
    let e = toml::from_str::<belt::Signal>(knots).unwrap_err();
    assert!(e.to_string().contains("exactly two numbers"), "{e}");
    let knots = "kind = \"schedule\"\nknots = [[0.0, 0.0], [1.0, 2.0]]\n";
    assert!(toml::from_str::<belt::Signal>(knots).is_ok());
}
