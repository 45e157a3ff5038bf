//! Issue 34 item 3: the `tanh_slip` law at its default scale, `μ tanh(v_t / v_s)` with
//! `v_s = contact::friction::spec::DEFAULT_SLIP_VELOCITY` (Ribaric (6.2) with `κ = 1/v_s`),
//! puts the speed loss within 1 % of its Coulomb limit (`v_s → 0`). (It is not the layouts'
//! default friction: `belt::BeltContact::default` explains why.)
//!
//! Reference (the Coulomb limit): the same drive at a quarter of the default scale, `v_s / 4`
//! (BENCHMARKS.md, "friction regularisation": on Table 6-1 at 10 N·m the flowing model's
//! speed loss falls from 0.05746 rad/s at 0.1 mm/s to 0.05696 at 0.05 mm/s and 0.05654 at
//! 0.0125 mm/s, Richardson limit 0.0565; measured 2026-12-05). Ribaric's κ = 40 s/m on the same
//! drive must miss it by far (0.1863 rad/s: the check discriminates). Three flowing runs of
//! about 0.85 s simulated each, 1–3 s of CPU each in release.

use belt::{BeltContact, Layout};
use contact::friction::FrictionSpec;
use contact::friction::spec::DEFAULT_SLIP_VELOCITY;
use drives::{SpeedLossConfig, speed_loss_sweep};
use flowing::belt::{FlowingBelt, FlowingSettings};

/// Speed loss Δω = ω₁ − ω₂ \[rad/s\] of Ribaric's Table 6-1 drive (flowing model, default
/// settings) at 62.8 rad/s under 10 N·m, with `friction` (settled to 2·10⁻⁵ rad/s between
/// 50 ms windows).
fn speed_loss(friction: FrictionSpec) -> f64 {
    let mut layout = Layout::table_6_1();
    layout.contact.friction = friction;
    let drive = layout.resolve().unwrap();
    let mut belt = FlowingBelt::new(&drive, &FlowingSettings::default()).unwrap();
    let settings = SpeedLossConfig {
        torques: vec![10.0],
        tolerance: 2e-5,
        ..SpeedLossConfig::default()
    };
    let (points, _) = speed_loss_sweep(&mut belt, &settings, |_, _| {})
        .unwrap_or_else(|f| panic!("{friction:?}: {}", f.error));
    points[0].delta_omega
}

#[test]
fn the_default_friction_is_within_one_percent_of_the_coulomb_limit() {
    let default = FrictionSpec::tanh_slip(BeltContact::default().friction.mu());
    let FrictionSpec::TanhSlip { mu, slip_velocity } = default else {
        panic!("FrictionSpec::tanh_slip is not tanh_slip: {default:?}");
    };
    assert_eq!(slip_velocity, DEFAULT_SLIP_VELOCITY);
    let d = speed_loss(default);
    let limit = speed_loss(FrictionSpec::TanhSlip {
        mu,
        slip_velocity: slip_velocity / 4.0,
    });
    let ribaric = speed_loss(FrictionSpec::Tanh { mu, kappa: 40.0 });
    eprintln!("Δω: default {d:.6}, v_s/4 {limit:.6}, κ = 40 {ribaric:.6} rad/s");
    assert!(limit > 0.0, "{limit}");
    assert!(
        (d - limit).abs() <= 0.01 * limit,
        "default {d} vs {limit} at v_s/4: {:+.2} %",
        100.0 * (d / limit - 1.0)
    );
    assert!(ribaric > 1.5 * limit, "κ = 40: {ribaric} vs {limit}");
}
