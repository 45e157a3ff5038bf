//! Validation of the flowing-material belt drive (Ribaric ch. 5–6, Table 6-1) against the
//! analytical speed loss of Bechtel et al. (6.3), physical invariants and a second (untruncated)
//! formulation.

use belt::Layout;
use contact::friction::FrictionSpec;
use drives::table_6_1;
use drives::{SpeedLossConfig, SpeedLossPoint, analytical_speed_loss, speed_loss_sweep};
use flowing::belt::{BeltReduction, FlowingBelt, FlowingSettings};

fn sweep(
    (cfg, settings): &(Layout, FlowingSettings), omega: f64, torques: &[f64], tol: f64,
) -> (Vec<SpeedLossPoint>, Vec<(f64, f64)>) {
    let mut belt = FlowingBelt::new(&cfg.resolve().unwrap(), settings).unwrap();
    let settings = SpeedLossConfig {
        omega_driver: omega,
        torques: torques.to_vec(),
        tolerance: tol,
        ..Default::default()
    };
    let mut history = Vec::new();
    let (points, _) = speed_loss_sweep(&mut belt, &settings, |_, s| {
        history.push((s.t, s.omega_driven))
    })
    .unwrap_or_else(|f| panic!("sweep failed: {} (points {:?})", f.error, f.points));
    (points, history)
}

/// Ribaric Table 6-1 with the flowing model's default settings (§6.1's 56-element loop, 20
/// free-node modes).
fn table_6_1_flowing() -> (Layout, FlowingSettings) {
    (table_6_1::layout(), FlowingSettings::default())
}

// Issue 8 / seed-000 note BELT-3, BELT-6: unloaded, the driven pulley turns at the driver's speed
// (to 5e-6 relative: 1.4e-6 with the co-rotated axial force of issue 34, below 1e-7 with the
// linear model of (5.5)), and the stationary mesh puts no ripple (no line at the element-passing
// frequency v/L_e) on the driven speed.
#[test]
fn unloaded_drive_has_no_speed_loss_and_no_mesh_ripple() {
    let omega = 62.8;
    let (points, history) = sweep(&table_6_1_flowing(), omega, &[0.0], 1e-7);
    let rel = points[0].delta_omega.abs() / omega;
    assert!(rel < 5e-6, "unloaded |Δω|/ω = {rel:e}");
    // last 0.1 s (400 steps of 0.25 ms): peak-to-peak of ω₂
    let tail: Vec<f64> = history.iter().rev().take(400).map(|h| h.1).collect();
    let (lo, hi) = tail
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &w| (a.min(w), b.max(w)));
    assert!((hi - lo) / omega < 1e-6, "ω₂ ripple {:e} rad/s", hi - lo);
}

// Issue 8: Δω grows monotonically with the torque, is nearly linear at low torque and grows with
// the driver speed. With the regularised friction (6.2) it is affine in ω: creep (∝ ω, Bechtel)
// plus the slip `atanh(F_T/μF_N)/κ` that the tanh law needs to carry the load, which does not
// depend on the speed. Hence Δω(ω) = Aω + B with A, B > 0, checked at three speeds.
#[test]
fn speed_loss_is_monotonic_nearly_linear_and_affine_in_speed() {
    let cfg = table_6_1_flowing();
    let (fast, _) = sweep(&cfg, 62.8, &[0.0, 4.0, 8.0], 2e-4);
    let d: Vec<f64> = fast.iter().map(|x| x.delta_omega).collect();
    assert!(d[0] < d[1] && d[1] < d[2], "{d:?}");
    let lin = (d[2] - d[0]) / (d[1] - d[0]);
    assert!((lin - 2.0).abs() < 0.2, "Δω(8)/Δω(4) = {lin}");
    // the penalty law and the regularised friction add slip: above Bechtel's line (note B1 (b))
    assert!(d[2] > analytical_speed_loss(0.05, 310.0, 152_000.0, 8.0, 62.8));
    let (mid, _) = sweep(&cfg, 42.7, &[0.0, 8.0], 1e-4);
    let (slow, _) = sweep(&cfg, 22.6, &[0.0, 8.0], 1e-4);
    let (dl, dm) = (slow[1].delta_omega, mid[1].delta_omega);
    assert!(dl < dm && dm < d[2], "grows with speed: {dl} {dm} {}", d[2]);
    let a = (d[2] - dl) / (62.8 - 22.6);
    let b = dl - a * 22.6;
    assert!(a > 0.0 && b > 0.0, "A = {a}, B = {b}");
    let affine = a * 42.7 + b;
    assert!(
        (dm / affine - 1.0).abs() < 0.03,
        "Δω(42.7) = {dm} vs affine {affine}"
    );
}

// Issue 8: truncated (20 free-node modes) and untruncated flowing models agree within 2 %.
#[test]
fn truncated_and_untruncated_models_agree() {
    let mut cfg = table_6_1_flowing();
    let (trunc, _) = sweep(&cfg, 62.8, &[0.0, 8.0], 2e-4);
    cfg.1.reduction = BeltReduction { free_modes: None };
    let (full, _) = sweep(&cfg, 62.8, &[0.0, 8.0], 2e-4);
    let (a, b) = (trunc[1].delta_omega, full[1].delta_omega);
    assert!(
        (a / b - 1.0).abs() < 0.02,
        "truncated {a} vs untruncated {b}"
    );
}

// Ribaric (6.3) / seed-000 note BELT-4: under Bechtel's assumptions (elastic belt: no
// viscoelastic β; rigid contact: penalty ×1000; Coulomb friction: κ = 4000 s/m) the model
// approaches the analytical line within 10 %. Long (≈ 4 s simulated): run with --ignored.
#[test]
#[ignore = "heavy: about 4 s of simulated time"]
fn stiff_elastic_contact_approaches_bechtel() {
    let mut cfg = table_6_1_flowing();
    cfg.0.damping.beta = 0.0;
    cfg.0.contact.friction = FrictionSpec::Tanh {
        mu: 1.2,
        kappa: 4000.0,
    };
    cfg.0.contact.penalty_linear *= 1000.0;
    cfg.0.contact.penalty_quadratic *= 1000.0;
    let (pts, _) = sweep(&cfg, 62.8, &[0.0, 10.0], 1e-5);
    let exact = analytical_speed_loss(0.05, 310.0, 152_000.0, 10.0, 62.8);
    let err = (pts[1].delta_omega - pts[0].delta_omega) / exact - 1.0;
    assert!(
        err.abs() < 0.1,
        "Δω {} vs Bechtel {exact} ({:+.1} %)",
        pts[1].delta_omega,
        100.0 * err
    );
}
