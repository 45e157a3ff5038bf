//! Steady means of the FEAD study (issue 34 item 6): the window means of the default
//! six-pulley drive on the flowing model against the nodal model (the second formulation:
//! Ribaric (5.7), rotating mesh, co-rotated axial force, against the flowing model's
//! (5.14), stationary mesh, linear axial force), and the tensioner arm's dry-friction flag
//! (`drives::fead::ArmFriction`).
//!
//! Measured 2026-12-06 (BENCHMARKS.md, "FEAD steady means"): with the spans' whole axial
//! force (elastic plus the viscous force of the β damping, which carries `β v dT/ds` over a
//! layer of length `β v` = 11–49 mm beyond each wrap) the flowing model's default loop agrees
//! with the nodal model within 3.4 % over the sweep 800–3500 rpm (41 % with the elastic force
//! alone) and within 1.2 % on every span but the two slack spans after the crank. Those carry
//! the flowing model's crank torque deficit (0.3–0.9 N m): its power balance returns energy
//! from the belt where the nodal belt dissipates it (issue 34, open). Cause (h-bal3,
//! flowing::belt::flowing_system module documentation): Ribaric's projection (5.14) is not
//! energy-consistent on the stationary mesh; at 800 rpm its linear elastic forces do +32.7 W
//! and −5.6 W and its damping forces +10.8 W on the flowing material (their Kelvin–Voigt
//! dissipation is 29.8 W). Lagrange's equations of the same model
//! (`FlowingBelt::with_lagrange_equations`; in `fead` `[models.flowing] equations = "lagrange"`) conserve energy
//! exactly and give a crank torque of 19.08 N m against the nodal model's 19.00 N m (18.29 N m
//! with (5.14)), but move the defect (10.7 N: 4.2 N elastic, 6.5 N viscous) into the reference
//! node's tangential balance,
//! so the crank's spans then miss its torque by 4.8 %. The tensioner's dry friction does not
//! separate the models (the engine orders keep the arm sliding both ways).

use drives::fead::{EngineOrder, FeadConfig, FeadModel, FeadPoint, run_fead};

/// The default drive with the flowing model's loop refined to the nodal model's 12 mm and
/// the reduction removed (`free_modes = "all"`).
fn refined(speeds: &[f64]) -> FeadConfig {
    let mut cfg = FeadConfig::default();
    cfg.engine.speeds_rpm = speeds.to_vec();
    cfg.models.flowing.mesh.span_element = 0.012;
    cfg.models.flowing.reduction.free_modes = None;
    cfg
}

/// Both models on `cfg`: (flowing, nodal) points.
fn both(cfg: &FeadConfig) -> (Vec<FeadPoint>, Vec<FeadPoint>) {
    let mut c = cfg.clone();
    c.model = FeadModel::Flowing;
    let flow = run_fead(&c, |_| {}).unwrap_or_else(|e| panic!("flowing: {e}"));
    c.model = FeadModel::Nodal;
    let nodal = run_fead(&c, |_| {}).unwrap_or_else(|e| panic!("nodal: {e}"));
    (flow.points, nodal.points)
}

fn spans(p: &FeadPoint) -> Vec<f64> {
    p.spans.iter().map(|s| s.tension.mean).collect()
}

// Reference: the nodal model (second formulation) on the same drive and sweep point. The
// default drive at 800 rpm from rest with its engine orders (both windows steady): every
// span's mean force (elastic plus viscous, the whole force the elements carry) within 3 % and
// the arm's mean angle within 1 mrad (0.03 N m of the spring's 30 N m/rad). The flowing model
// runs on the nodal model's 12 mm loop without reduction. Measured 2026-12-06 (h-bal2): flowing
// 273.7, 303.6, 405.8, 405.0, 432.0, 515.3 N against nodal 266.2, 297.3, 406.2, 407.3, 434.9,
// 518.8 N (+2.8 % the largest), arm 0.3705 both; on the default loop (50 mm spans, 12 free
// modes) +3.1 % on crank → power steering. What separates the slack spans (checked here as
// well): the flowing model's crank torque is 0.87 N m below the nodal model's (18.12 against
// 19.00 N m) while the accessories' loads are the same, so the crank's spans differ by that
// torque over its radius (slack +7.5 N, tight −3.5 N: 11.0 N against (19.00 − 18.12)/0.075 =
// 11.6 N); the power balances show why: the flowing belt returns 35 W to the pulleys (its
// damping forces do −10 W on the advected material), the nodal belt absorbs 40 W (sliding
// 9.5 W, damping 25.8 W). About 35 s of CPU in release (the nodal point most of it).
#[test]
fn flowing_and_nodal_steady_means_agree_at_800_rpm() {
    let cfg = refined(&[800.0]);
    let (flow, nodal) = both(&cfg);
    let (f, n) = (&flow[0], &nodal[0]);
    eprintln!(
        "flowing {:?} arm {:?}; nodal {:?} arm {:?}",
        spans(f),
        f.arm_angle,
        spans(n),
        n.arm_angle
    );
    assert!(f.steady && n.steady);
    for ((a, b), s) in spans(f).iter().zip(spans(n)).zip(&f.spans) {
        assert!(
            (a / b - 1.0).abs() < 0.03,
            "span {}→{}: flowing {a:.1} N, nodal {b:.1} N",
            s.from,
            s.to
        );
    }
    let arm = |p: &FeadPoint| p.arm_angle.expect("the default drive has a tensioner").mean;
    assert!((arm(f) - arm(n)).abs() < 1e-3, "{} {}", arm(f), arm(n));
    // the spans' gap at the crank (slack above, tight below the nodal model's) is the crank's
    // torque deficit over its radius (within 25 %), not the accessories'
    let crank = |p: &FeadPoint| -p.report.pulleys[0].torque_n_m;
    let deficit = (crank(n) - crank(f)) / cfg.drive.pulleys[0].radius;
    let (sf, sn) = (spans(f), spans(n));
    let gap = (sf[0] - sn[0]) - (sf[5] - sn[5]);
    eprintln!("crank spans' gap {gap:.1} N, crank torque deficit over radius {deficit:.1} N");
    assert!(deficit > 0.0 && (gap / deficit - 1.0).abs() < 0.25);
    // the engine orders keep the arm sliding both ways through its dry friction
    for p in [f, n] {
        let af = p.arm_friction.as_ref().expect("dry friction at the pivot");
        assert!(!af.held && af.stick_fraction < 1.0, "{af:?}");
    }
}

// Reference: as above, at 2500 rpm after the sweep's 800 and 1500 rpm points (no dry
// friction). With the whole force measure (elastic plus viscous) the 57 mm alternator →
// tensioner span is compared directly like the others (its elastic mid-span force departed
// from its ends' balance by the β v layer; the viscous force closes it). The four spans from
// the alternator to the crank within 1.5 %, the two slack spans after the crank within 4 %
// (their excess is the flowing model's crank torque deficit, 800 rpm test). Measured
// 2026-12-06 with dry friction (not this test's configuration): flowing 305.0, 334.6, 433.5,
// 432.2, 459.6, 543.1 N against nodal 295.4, 326.0, 434.4, 434.8, 461.8, 545.1 N (+3.2, +2.6,
// −0.2, −0.6, −0.5, −0.4 %).
#[test]
#[ignore = "heavy: about 2.6 min of CPU (nodal sweep 800 → 1500 → 2500 rpm)"]
fn flowing_and_nodal_steady_means_agree_at_2500_rpm() {
    let mut cfg = refined(&[800.0, 1500.0, 2500.0]);
    if let Some(t) = cfg.drive.tensioner.as_mut() {
        t.dry_friction = 0.0;
    }
    let (flow, nodal) = both(&cfg);
    let (f, n) = (&flow[2], &nodal[2]);
    eprintln!("flowing {:?}; nodal {:?}", spans(f), spans(n));
    assert!(f.steady && n.steady);
    for (k, (a, b)) in spans(f).iter().zip(spans(n)).enumerate() {
        let tol = if k < 2 { 0.04 } else { 0.015 };
        assert!((a / b - 1.0).abs() < tol, "span {k}: {a:.1} N, {b:.1} N");
    }
}

// Reference: the regularised dry friction's stick band `|θ̇| ≤ ω_f` (belt::Tensioner, Ribaric
// (6.2)). On the default drive at 800 rpm (flowing model, default loop) the engine orders
// swing the arm both ways faster than ω_f = 0.05 rad/s (measured 2026-12-05: rates −0.66 …
// +0.60 rad/s, 48 % of the steps in the band): not held. With a steady crank the arm comes
// to rest: every step in the band, held. Without dry friction there is nothing to report.
#[test]
fn the_arm_is_flagged_held_only_when_it_does_not_slide_both_ways() {
    let mut cfg = FeadConfig::default();
    cfg.engine.speeds_rpm = vec![800.0];
    let dithered = run_fead(&cfg, |_| {}).unwrap();
    let af = dithered.points[0]
        .arm_friction
        .clone()
        .expect("dry friction");
    eprintln!("orders: {af:?}");
    let w = cfg.drive.tensioner.expect("tensioner").friction_rate;
    assert!(!af.held && af.rate_range[0] < -w && af.rate_range[1] > w);
    cfg.engine.orders = vec![EngineOrder {
        order: 2.0,
        amplitude: 0.0,
        phase: 0.0,
    }];
    let steady = run_fead(&cfg, |_| {}).unwrap();
    let af = steady.points[0].arm_friction.clone().expect("dry friction");
    eprintln!("steady crank: {af:?}");
    assert!(af.held && af.stick_fraction == 1.0, "{af:?}");
    if let Some(t) = cfg.drive.tensioner.as_mut() {
        t.dry_friction = 0.0;
    }
    let free = run_fead(&cfg, |_| {}).unwrap();
    assert!(free.points[0].arm_friction.is_none());
}
