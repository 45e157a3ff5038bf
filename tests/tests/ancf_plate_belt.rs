//! Validation of the three-dimensional plate-belt drive (Kerkkänen ch. 4, §4.5–4.6) and its
//! comparison with Bechtel's steady model and with the planar ANCF belt. Quick checks run in
//! every `cargo test`; the long simulations of the issue are `#[ignore]`d (run them with
//! `cargo test --release -p flowmbd-validation --test integration ancf_plate_belt:: -- --ignored`).

use ancf::belt_drive::{BeltDrive, BeltDriveSpec, BeltFriction, InitialOptions, post as post2d};
use ancf::plate::belt_drive::post::{line_samples, span_states};
use ancf::plate::belt_drive::{PlateBeltDrive, PlateDriveSpec};
use belt::{Motion, Signal};
use drives::plate_study::{PlateStudyConfig, plate_run, plate_setup, wide_pulley_case};
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, JacobianMode, NewtonUpdate, State};
use std::f64::consts::PI;

/// Central differences of the forces against the analytic tangent at `(t, q, v)`.
fn check_tangent(d: &PlateBeltDrive, t: f64, q: &[f64], v: &[f64]) {
    let n = d.n_q();
    let tg = d
        .force_tangent(t, q, v, &mut mbd_core::Workspace::new())
        .unwrap()
        .unwrap();
    let k = tg.stiffness.to_dense();
    let c = tg.damping.to_dense();
    let (mut fp, mut fm) = (vec![0.0; n], vec![0.0; n]);
    let (mut worst_k, mut worst_c) = (0.0f64, 0.0f64);
    let kmax = (0..n).map(|i| k[(i, i)].abs()).fold(0.0, f64::max);
    let cmax = (0..n).map(|i| c[(i, i)].abs()).fold(0.0, f64::max);
    for j in 0..n {
        let h = 1e-8;
        let mut qp = q.to_vec();
        qp[j] += h;
        d.forces(t, &qp, v, &mut fp, &mut mbd_core::Workspace::new())
            .unwrap();
        qp[j] -= 2.0 * h;
        d.forces(t, &qp, v, &mut fm, &mut mbd_core::Workspace::new())
            .unwrap();
        for i in 0..n {
            worst_k = worst_k.max((-(fp[i] - fm[i]) / (2.0 * h) - k[(i, j)]).abs());
        }
        let hv = 1e-7;
        let mut vp = v.to_vec();
        vp[j] += hv;
        d.forces(t, q, &vp, &mut fp, &mut mbd_core::Workspace::new())
            .unwrap();
        vp[j] -= 2.0 * hv;
        d.forces(t, q, &vp, &mut fm, &mut mbd_core::Workspace::new())
            .unwrap();
        for i in 0..n {
            worst_c = worst_c.max((-(fp[i] - fm[i]) / (2.0 * hv) - c[(i, j)]).abs());
        }
    }
    println!("tangent check: |ΔK| {worst_k:e} of {kmax:e}, |ΔC| {worst_c:e} of {cmax:e}");
    assert!(worst_k < 1e-5 * kmax, "stiffness {worst_k:e} vs {kmax:e}");
    assert!(worst_c < 1e-5 * cmax, "damping {worst_c:e} vs {cmax:e}");
}

/// The equilibrium on the pulleys with the belt travelling at `speed` along its mid-line plus a
/// 1 % speed variation (some points creep, some slip), pulleys turning.
fn moving_state(d: &PlateBeltDrive, speed: f64) -> (Vec<f64>, Vec<f64>) {
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    let mut v = d.travelling_velocity(&init.q, speed);
    for (i, x) in v.iter_mut().enumerate().take(d.n_belt()) {
        *x *= 1.0 + 0.01 * ((i / 9) as f64).sin();
    }
    for p in 0..d.pulleys().len() {
        if let Some(j) = d.pulley_dof(p) {
            v[j] *= 0.97;
        }
    }
    (init.q, v)
}

// Reference: central finite differences of the generalized forces of Model 2 (membrane plate,
// creep-rate friction over the default 9 × 3 and over 9 × 9 points per element, free driven
// pulley): the analytic tangent is −∂f/∂q, −∂f/∂v including the coupling through the driven
// pulley's speed.
#[test]
fn analytic_tangent_matches_finite_differences() {
    for across in [None, Some(9)] {
        let mut spec = PlateDriveSpec::kerkkanen_model2();
        spec.contact.points_across = across;
        let d = PlateBeltDrive::new(spec).unwrap();
        let (q, v) = moving_state(&d, 20.0);
        check_tangent(&d, 1.2, &q, &v);
    }
}

// Reference: as above for Model 1 with bending on, the driver centre moving by (4.46)
// (t = 0.03 s), crowned pulleys and flanges pressed into the belt edges (tanh friction).
#[test]
fn tangent_with_bending_shift_crown_and_flanges_matches_finite_differences() {
    let mut spec = PlateDriveSpec::kerkkanen_model1();
    let w = spec.belt.width;
    for p in &mut spec.pulleys {
        p.crown = 0.5;
        p.flanges = Some([-0.5 * w + 2e-3, 0.5 * w - 2e-3]);
    }
    spec.contact.friction = BeltFriction::Tanh {
        mu: 1.2,
        kappa: 50.0,
    };
    let d = PlateBeltDrive::new(spec).unwrap();
    let (q, v) = moving_state(&d, 0.5);
    check_tangent(&d, 0.03, &q, &v);
}

// Analytical (uniaxial plane-stress St. Venant–Kirchhoff membrane): Model 2's belt at rest on
// the pulleys is stretched uniformly along its length, so with λ = 1 + ε (4.9) the membrane
// force is F = k λ (λ² − 1)/2 and the Green-measure tension k ε is the 50 N of the construction
// less the shortening of the path by the contact penetration d (Δλ/λ = 2π d / L_p). The strain
// measures spread as in Fig. 4.12 (seed note: 20–25 % between Green and true strain at 50 N):
// true 1 − 1/λ, printed Almansi √(2 − 1/λ²) − 1. Force balance: each pulley carries the pull of
// both spans, 2F.
#[test]
fn model_2_initial_state_is_the_uniaxial_membrane() {
    let d = PlateBeltDrive::new(PlateDriveSpec::kerkkanen_model2()).unwrap();
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    assert!(init.residual < 1e-8, "residual {}", init.residual);
    assert!(init.holding_force[0].abs() < 0.05 && init.holding_force[1].abs() < 1e-6);
    let v0 = vec![0.0; d.n_q()];
    let k = d.spec().belt.axial_stiffness();
    let recs = d.contact_records(0.0, &init.q, &v0);
    let pen = recs.iter().map(|r| r.penetration).sum::<f64>() / recs.len() as f64;
    let lp = d.path().length();
    let lam_path = (lp - 2.0 * PI * pen) / d.spec().belt.length;
    let states = span_states(&d, &init.q, &v0);
    for s in &states {
        let lam = 1.0 + s.tension[0] / k;
        println!(
            "span: T green {:.3} true {:.3} almansi {:.3} N, membrane {:.3} N, λ {lam:.5} (path {lam_path:.5})",
            s.tension[0], s.tension[1], s.tension[2], s.membrane_force
        );
        assert!((lam - lam_path).abs() < 2e-3, "λ {lam} vs {lam_path}");
        let f = k * lam * (lam * lam - 1.0) / 2.0;
        assert!(
            (s.membrane_force - f).abs() < 2e-3 * f,
            "{} vs {f}",
            s.membrane_force
        );
        assert!((s.tension[1] - k * (1.0 - 1.0 / lam)).abs() < 1e-3 * s.tension[1]);
        assert!((s.tension[2] - k * ((2.0 - 1.0 / (lam * lam)).sqrt() - 1.0)).abs() < 1e-2);
        let spread = 1.0 - s.tension[1] / s.tension[0];
        assert!((0.18..0.22).contains(&spread), "true vs Green {spread}");
    }
    for (force, torque) in d.pulley_loads(0.0, &init.q, &v0) {
        let f = states[0].membrane_force;
        let mag = force[0].hypot(force[1]);
        assert!(
            (mag - 2.0 * f).abs() < 5e-3 * f,
            "hub load {mag} vs 2F {}",
            2.0 * f
        );
        assert!(force[2].abs() < 1e-9 && torque.abs() < 1e-3);
    }
}

/// The wide-pulley case (drives::plate_study::wide_pulley_case) and its planar equivalent
/// (per-length contact = per-area × width, planar bending scaled by α₂ = 0.01).
fn wide_case(omega: f64, torque: f64) -> (PlateDriveSpec, BeltDriveSpec) {
    let p = wide_pulley_case(omega, torque);
    let planar = p.planar_equivalent(0.01).unwrap();
    (p, planar)
}

// Second formulation: on the wide-pulley case with no out-of-plane load the plate belt at
// rest on the pulleys is the planar ANCF belt (Kerkkänen ch. 3) extruded over the width: same
// axial force and same penetration (pressure × width = force per length). The plate's
// Green-measure tension k ε (4.9) is turned into the St Venant–Kirchhoff force k λ(λ² − 1)/2,
// λ = 1 + ε (the uniaxial membrane above), which is what the planar belt reports (the axial
// force of its law, BeltElement::axial_force).
#[test]
fn plate_belt_at_rest_matches_the_planar_belt() {
    let (p, planar) = wide_case(100.0, 0.5);
    let d3 = PlateBeltDrive::new(p).unwrap();
    let i3 = d3.initial_state(&InitialOptions::default()).unwrap();
    let d2 = BeltDrive::new(planar).unwrap();
    let i2 = d2.initial_state(&InitialOptions::default()).unwrap();
    let v0 = vec![0.0; d3.n_q()];
    let w = d3.spec().belt.width;
    let s3 = line_samples(&d3, &i3.q, &v0, 0.5 * w, 4);
    let k = d3.spec().belt.axial_stiffness();
    let t3 = s3
        .iter()
        .map(|s| {
            let lam = 1.0 + s.tension[0] / k;
            k * lam * (lam * lam - 1.0) / 2.0
        })
        .sum::<f64>()
        / s3.len() as f64;
    let pen3 = d3
        .contact_records(0.0, &i3.q, &v0)
        .iter()
        .map(|r| r.penetration)
        .fold(0.0, f64::max);
    let pen2 = d2
        .contact_records(0.0, &i2.q, &vec![0.0; d2.n_q()])
        .iter()
        .map(|r| r.penetration)
        .fold(0.0, f64::max);
    println!(
        "tension: plate {t3:.4} N, planar {:.4} N; penetration: plate {pen3:e} m, planar {pen2:e} m",
        i2.mean_tension
    );
    assert!((t3 - i2.mean_tension).abs() < 5e-3 * i2.mean_tension);
    assert!((pen3 - pen2).abs() < 2e-2 * pen2);
}

/// Model 2 with a constant driver speed and load from a belt already travelling at the driver's
/// surface speed (skips the 1 s ramp), run for `t_end` with mbd-core's generalized-α.
fn model2_constant(t_end: f64) -> (PlateBeltDrive, State) {
    let mut spec = PlateDriveSpec::kerkkanen_model2();
    spec.pulleys[0].motion = Motion::speed(Signal::constant(500.0));
    spec.pulleys[1].motion = Motion::load(0.00025, Signal::constant(2.0));
    let d = PlateBeltDrive::new(spec).unwrap();
    let init = d.initial_state(&InitialOptions::default()).unwrap();
    let v = d.travelling_velocity(&init.q, 25.0);
    let cfg = AlphaConfig {
        rho_inf: 0.6,
        h: 5e-5,
        newton_atol: 1e-7,
        max_newton_iterations: 25,
        jacobian: JacobianMode::Analytic,
        update: NewtonUpdate::EveryIteration,
        max_halvings: 10,
        ..AlphaConfig::default()
    };
    let sol = GeneralizedAlpha::new(cfg)
        .integrate(&d, State::new(0.0, init.q, v), t_end, |_| {})
        .unwrap();
    (d, sol.state)
}

// Invariants of the running Model 2 (Kerkkänen §4.6): the driven pulley turns slower than the
// driver (the belt creeps and slips on it), the contact forces carry the applied 2 N·m once the
// pulley runs steadily, and that torque is the friction integrated over the contact area times
// the lever arm (the normal force has no moment about the axis) — R ∫ f dA within the
// penetration's share d/R of the radius.
#[test]
fn running_model_2_contact_carries_the_load() {
    let (d, s) = model2_constant(0.04);
    let w_driven = d.pulley_speed(1, s.t, &s.v);
    let (_, torque) = d.pulley_loads(s.t, &s.q, &s.v)[1];
    println!(
        "t = {}: driven {w_driven:.2} rad/s, contact torque {torque:.4} N·m",
        s.t
    );
    assert!(
        w_driven < 0.97 * 500.0 && w_driven > 0.8 * 500.0,
        "{w_driven}"
    );
    assert!((torque - 2.0).abs() < 0.1, "contact torque {torque}");
    // friction integrated over the driven pulley's contact area (9 × 3 points per element)
    let quad = d.contact_quadrature();
    let a = d.element_length();
    let recs = d.contact_records(s.t, &s.q, &s.v);
    let mut integral = 0.0;
    for r in recs.iter().filter(|r| r.pulley == 1) {
        let x = r.s_material - r.element as f64 * a;
        let wq = quad
            .iter()
            .find(|(qx, qy, _)| (qx - x).abs() < 1e-12 && (qy - r.y).abs() < 1e-12)
            .map(|q| q.2)
            .unwrap();
        integral += r.friction[0] * wq;
    }
    let lever = -integral * 0.05;
    println!("R ∫ f dA = {lever:.4} N·m");
    assert!(
        (lever - torque).abs() < 0.02 * torque.abs(),
        "{lever} vs {torque}"
    );
}

// Kerkkänen Fig. 4.10 (Model 1): with the low Young's modulus the driven pulley lags the driver
// noticeably during the acceleration (the belt slips on the heavy driven pulley, I = 0.25
// kg·m²); after 0.1 s of the ramp (3.29) it is far below the driver. The belt is tensioned by
// the driver-centre shift (4.46): the slack span keeps a positive tension.
#[test]
fn model_1_driven_pulley_lags_during_the_ramp() {
    let mut c = PlateStudyConfig::kerkkanen_model1();
    c.t_end = 0.1;
    c.output.history_interval = 0.01;
    let (d, init) = plate_setup(&c).unwrap();
    let end = plate_run(&c, &d, &init, std::time::Instant::now(), |_, _| {
        Ok::<(), ()>(())
    })
    .unwrap();
    assert!(end.failure.is_none(), "{:?}", end.failure);
    let s = end.summary;
    println!(
        "t = {}: driver {:.3} driven {:.3} rad/s, tensions {:.2} / {:.2} N",
        s.run.t_end,
        s.run.omega_driver_end,
        s.run.omega_driven_end,
        s.run.tension_tight,
        s.run.tension_slack
    );
    assert!((s.run.omega_driver_end - 12.0 * 0.05 / 0.55).abs() < 1e-9);
    assert!(s.run.omega_driven_end > 0.0 && s.run.omega_driven_end < 0.5 * s.run.omega_driver_end);
    assert!(s.run.tension_slack > 5.0 && s.run.tension_tight > s.run.tension_slack);
}

// Kerkkänen §4.6, Model 2 (Table 4.1, Figs 4.12, 4.14–4.18), the whole run of the study
// (ramp to 500 rad/s and 2 N·m at 1.0 s, steady to 1.3 s):
// * steady driven speed ≈ 10 % below the driver (thesis Fig. 4.16: ≈ 450 vs 500 rad/s);
// * Bechtel's model (seed note §6.2 closure) 15.2 % below (thesis, read off Fig. 4.14: 14.6 %);
// * the contact forces carry the applied 2 N·m; the membrane forces of the spans balance it
//   with the belt's momentum flux, R[(F₁ − Gv₁) − (F₂ − Gv₂)] = M;
// * the strain-based tensions do not (thesis: Green ≈ 1.4 N·m, the other measures less).
#[test]
#[ignore = "long run: Model 2 for 1.3 s (26 000 generalized-α steps, ~10 min on a free core)"]
fn model_2_steady_slip_and_torques() {
    let c = PlateStudyConfig::kerkkanen_model2();
    let (d, init) = plate_setup(&c).unwrap();
    let end = plate_run(&c, &d, &init, std::time::Instant::now(), |_, _| {
        Ok::<(), ()>(())
    })
    .unwrap();
    assert!(end.failure.is_none(), "{:?}", end.failure);
    let s = end.summary;
    println!("{}", serde_json::to_string_pretty(&s).unwrap());
    let deficit = 1.0 - s.omega_driven_mean / s.omega_driver_mean;
    let analytic = 1.0 - s.analytical_omega_driven / 500.0;
    assert!((deficit - 0.10).abs() < 0.03, "FE deficit {deficit}");
    assert!(
        (analytic - 0.152).abs() < 2e-3,
        "analytical deficit {analytic}"
    );
    assert!((analytic - 0.146).abs() < 0.01, "thesis: 14.6 %");
    assert!(
        analytic > deficit,
        "the analytical model predicts more slip"
    );
    assert!((s.contact_torque_driven - 2.0).abs() < 0.1);
    assert!(s.tension_torque.green < 2.0 && s.tension_torque.green > 0.5);
    assert!(s.tension_torque.r#true < s.tension_torque.green);
    assert!(s.tension_torque.almansi < s.tension_torque.green);
    // momentum flux G v = ρA v²/λ of each span (mass conservation: v_o = v/λ), λ = 1 + ε (4.9)
    let k = c.drive.belt.axial_stiffness();
    let rho_a = c.drive.belt.mass_per_length();
    let u = |m: usize| {
        let lam = 1.0 + s.span_tensions[m].green / k;
        s.membrane_forces[m] - rho_a * s.span_speeds[m] * s.span_speeds[m] / lam
    };
    let balance = (u(0) - u(1)) * d.pulleys()[1].radius;
    println!(
        "membrane torque {:.4} N·m, with the momentum flux {balance:.4} N·m",
        s.membrane_torque
    );
    assert!((balance - 2.0).abs() < 0.1, "{balance}");
}

// The planar and the plate belt on the wide-pulley case agree in operation too: driver ramped
// to 100 rad/s, load 0.5 N·m, compared 0.1 s after the ramp (no out-of-plane motion, so the
// plate is the planar belt extruded over the width: second formulation).
#[test]
#[ignore = "long run: the plate and the planar belt for 0.3 s each (~3 min)"]
fn plate_and_planar_belts_agree_in_operation() {
    let (p, planar) = wide_case(100.0, 0.5);
    let d3 = PlateBeltDrive::new(p).unwrap();
    let i3 = d3.initial_state(&InitialOptions::default()).unwrap();
    let d2 = BeltDrive::new(planar).unwrap();
    let i2 = d2.initial_state(&InitialOptions::default()).unwrap();
    let cfg = AlphaConfig {
        rho_inf: 0.6,
        h: 1e-4,
        newton_atol: 1e-7,
        max_newton_iterations: 25,
        max_halvings: 10,
        ..AlphaConfig::default()
    };
    let t_end = 0.3;
    let s3 = GeneralizedAlpha::new(cfg)
        .integrate(
            &d3,
            State::new(0.0, i3.q.clone(), vec![0.0; d3.n_q()]),
            t_end,
            |_| {},
        )
        .unwrap()
        .state;
    let s2 = GeneralizedAlpha::new(cfg)
        .integrate(
            &d2,
            State::new(0.0, i2.q.clone(), vec![0.0; d2.n_q()]),
            t_end,
            |_| {},
        )
        .unwrap()
        .state;
    let w3 = d3.pulley_speed(1, t_end, &s3.v);
    let w2 = d2.pulley_speed(1, t_end, &s2.v);
    let t3 = span_states(&d3, &s3.q, &s3.v);
    let t2 = post2d::span_tensions(&d2, &s2.q);
    println!(
        "driven: plate {w3:.4} planar {w2:.4} rad/s; spans plate {:.2}/{:.2} planar {:.2}/{:.2} N",
        t3[0].tension[0], t3[1].tension[0], t2[0], t2[1]
    );
    assert!((w3 - w2).abs() < 2e-3 * 100.0, "{w3} vs {w2}");
    for k in 0..2 {
        assert!((t3[k].tension[0] - t2[k]).abs() < 0.02 * t2[k]);
    }
}

// The contact grid across the width (issue 37 item 3): the default 9 × 3 Gauss points per
// element on flat pulleys against the 9 × 9 of Kerkkänen's 81 points (reference: the 9 × 9
// solution), on Model 2 in steady operation (driver 500 rad/s, 2 N·m, the belt started at
// the driver's surface speed) over 0.02 s with the study's integrator. The yardstick is the
// study's (BENCHMARKS.md, plate-belt drive, h-plate6): 9 × 3 is accepted where it differs
// from 9 × 9 about as much as 9 × 9 differs from itself at the Newton tolerance 10⁻⁶ m
// instead of 10⁻⁷ m (printed beside it).
#[test]
fn three_points_across_agree_with_nine_on_model_2() {
    use ancf::belt_drive::SimulationConfig;
    use mbd_core::integrators::Stepper;
    let run = |across: usize, atol: f64| {
        let mut spec = PlateDriveSpec::kerkkanen_model2();
        spec.pulleys[0].motion = Motion::speed(Signal::constant(500.0));
        spec.pulleys[1].motion = Motion::load(0.00025, Signal::constant(2.0));
        spec.contact.points_across = Some(across);
        let d = PlateBeltDrive::new(spec).unwrap();
        let init = d.initial_state(&InitialOptions::default()).unwrap();
        let v = d.travelling_velocity(&init.q, 25.0);
        let cfg = SimulationConfig {
            h: 5e-5,
            newton_atol: atol,
            ..PlateStudyConfig::default().integrator
        };
        let mut st = GeneralizedAlpha::new(cfg.alpha_params())
            .stepper(&d, State::new(0.0, init.q, v))
            .unwrap();
        // the driven speed and the contact torque averaged over 0.01–0.02 s (11 samples, as
        // the study's summary averages them), the span tensions at 0.02 s
        let (mut speed, mut torque) = (0.0, 0.0);
        for k in 0..=10 {
            st.advance_to(&d, 0.01 + 1e-3 * k as f64, &mut ()).unwrap();
            let s = st.state();
            speed += d.pulley_speed(1, s.t, &s.v) / 11.0;
            torque += d.pulley_loads(s.t, &s.q, &s.v)[1].1 / 11.0;
        }
        let s = st.state().clone();
        let spans = span_states(&d, &s.q, &s.v);
        (speed, torque, [spans[0].tension[0], spans[1].tension[0]])
    };
    let (w9, m9, t9) = run(9, 1e-7);
    let (w3, m3, t3) = run(3, 1e-7);
    let (wn, mn, tn) = run(9, 1e-6);
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    println!(
        "driven {w9:.6} / {w3:.6} rad/s ({:.1e}), torque {m9:.6} / {m3:.6} N·m ({:.1e}), \
         spans {:.5}, {:.5} / {:.5}, {:.5} N ({:.1e}, {:.1e}); 9 × 9 at 1e-6 m: {:.1e}, {:.1e}, \
         {:.1e}, {:.1e}",
        rel(w3, w9),
        rel(m3, m9),
        t9[0],
        t9[1],
        t3[0],
        t3[1],
        rel(t3[0], t9[0]),
        rel(t3[1], t9[1]),
        rel(wn, w9),
        rel(mn, m9),
        rel(tn[0], t9[0]),
        rel(tn[1], t9[1])
    );
    // bounds: about 5× the Newton-tolerance spread of 9 × 9 on this transient window (at
    // 0.02 s: 1.9·10⁻⁵ driven, 9.4·10⁻⁴ torque, 7.3·10⁻⁴ slack span, instantaneous values)
    assert!(rel(w3, w9) < 1e-4, "driven {w3} vs {w9}");
    assert!(rel(m3, m9) < 5e-3, "torque {m3} vs {m9}");
    for k in 0..2 {
        assert!(rel(t3[k], t9[k]) < 1e-3, "span {k}: {} vs {}", t3[k], t9[k]);
    }
}
