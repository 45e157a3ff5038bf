//! The speed-loss procedure's runaway test (`drives::speed_loss::gross_slip_bound`) reads the
//! running mean of the speed loss over at least a quarter window
//! (`drives::speed_loss::RUNAWAY_MIN_FRACTION`), not single steps: near the Coulomb limit the
//! ANCF belt's speed loss oscillates about its mean by more than the bound's margin over the
//! steady creep. The runaway itself (a load above the capacity) is still found:
//! `flowmbd-validation` `belt_drive_outputs::flowing_gross_slip_is_a_result_and_the_sweep_goes_on`.

use contact::friction::FrictionSpec;
use drives::ModelKind;
use drives::speed_loss_study::{SpeedLossStudyConfig, run_case};

/// Δω \[rad/s\] at 10 and 30 N·m of Ribaric's Table 6-1 drive at 62.8 rad/s on the ANCF belt
/// with `μ tanh(v_t / v_s)`, μ = 1.2, at `slip_velocity` \[m/s\] (settled to 2·10⁻⁴ rad/s
/// between 0.2 s windows), `None` for a point marked as a gross slip, and the closed form
/// (Bechtel (6.3), Grashof's creep) at the same torques.
fn ancf_speed_losses(slip_velocity: f64) -> (Vec<Option<f64>>, Vec<f64>) {
    let mut c = SpeedLossStudyConfig {
        model: ModelKind::Ancf,
        omegas: vec![62.8],
        ..Default::default()
    };
    c.drive.contact.friction = FrictionSpec::TanhSlip {
        mu: 1.2,
        slip_velocity,
    };
    c.procedure.torques = vec![10.0, 30.0];
    c.procedure.tolerance = 2e-4;
    c.procedure.window = 0.2;
    let (case, _, _) =
        run_case(&c, 62.8, |_, _| {}).unwrap_or_else(|e| panic!("v_s = {slip_velocity}: {e:?}"));
    let dw = case
        .points
        .iter()
        .map(|p| p.gross_slip.is_none().then_some(p.delta_omega))
        .collect();
    (dw, case.analytical)
}

// Measured 2026-12-07 (BENCHMARKS.md, "friction regularisation"): at v_s = 0.125 mm/s the
// single-step test flagged the 30 N·m point as a runaway at t = 2.72 s (0.278 rad/s above the
// bound's 0.275 rad/s) where the point settles at 0.2398 rad/s; at 0.5 mm/s it gives 0.2400.
// Reference: the same drive at 0.5 mm/s, where the oscillation stays below the bound (the
// regularisation moves Δω by 0.1 % between the two scales), and Grashof's closed form at
// 30 N·m (0.2469 rad/s; the ANCF belt's bending stiffness puts it 2.9 % below).
#[test]
#[ignore = "heavy: two ANCF speed-loss sweeps, about 4 min of CPU"]
fn a_steady_point_near_the_coulomb_limit_is_not_a_runaway() {
    let (sharp, closed_form) = ancf_speed_losses(1.25e-4);
    let (reference, _) = ancf_speed_losses(5e-4);
    eprintln!("Δω at 10, 30 N m: v_s = 0.125 mm/s {sharp:?}, 0.5 mm/s {reference:?}");
    for (k, (s, r)) in sharp.iter().zip(&reference).enumerate() {
        let r = r.expect("the 0.5 mm/s reference is steady");
        let s = s.unwrap_or_else(|| panic!("point {k} marked as a runaway at 0.125 mm/s"));
        assert!((s / r - 1.0).abs() < 0.01, "point {k}: {s} against {r}");
    }
    assert!(
        (sharp[1].unwrap() / closed_form[1] - 1.0).abs() < 0.05,
        "{closed_form:?}"
    );
}
