//! Any-layout belt drives (issue 17 items 4 and 6): the flowing-material model on N pulleys
//! with a tensioner, against hand statics, the two-pulley model, and invariants.

use belt::{BeltModel, Layout, Motion};
use contact::friction::FrictionSpec;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, State};
use mbd_core::{SecondOrderSystem, Validate};

use crate::common;
use common::{flowing, four_pulleys, four_pulleys_settings, nodal};

// Static tension equal in all spans at zero load on frictionless idlers (issue 17 item 6):
// the belt at rest, friction off (μ = 0); every span carries the same tension, within 0.2 %.
// The arm stays within 1 mrad of the hand-statics angle it was laid out at: the discrete
// mounted state is not exactly in equilibrium (the penalty force of an arc-end node acts on its
// whole tributary length, half of it on the span), so the belt settles by a few µm and the arm
// with it (0.67 mrad here, ≈ 2 % of T0).
#[test]
fn static_span_tensions_are_equal_on_frictionless_pulleys() {
    let mut cfg = four_pulleys(0.0);
    cfg.contact.friction = FrictionSpec::Tanh {
        mu: 0.0,
        kappa: 40.0,
    };
    cfg.validate().unwrap();
    let (belt, res) = flowing(&cfg, &four_pulleys_settings());
    eprintln!(
        "T0 {} N, arm {:?}, wraps {:?} deg, belt {} m",
        res.tension(),
        res.arm(),
        res.wraps()
            .iter()
            .map(|w| w.to_degrees())
            .collect::<Vec<_>>(),
        res.belt_length()
    );
    let q = belt.static_state().unwrap();
    let k = belt.coords.arm_dof().unwrap();
    let v = vec![0.0; q.len()];
    let snap = belt.snapshot(0.0, &q, &v).unwrap();
    assert_eq!(snap.spans.len(), 4);
    let tensions: Vec<f64> = snap.spans.iter().map(|s| s.tension).collect();
    eprintln!(
        "span tensions {tensions:?} N (T0 {} N), arm {} rad",
        res.tension(),
        q[k]
    );
    let mean = tensions.iter().sum::<f64>() / 4.0;
    for s in &snap.spans {
        assert!(
            (s.tension / mean - 1.0).abs() < 2e-3,
            "span {}→{}: {} N vs mean {mean} N",
            s.from,
            s.to,
            s.tension,
        );
    }
    assert!(
        (mean / res.tension() - 1.0).abs() < 0.05,
        "mean {mean} vs T0 {}",
        res.tension()
    );
    assert!(
        q[k].abs() < 1e-3,
        "arm moved {} rad from the hand statics",
        q[k]
    );
}

// Tensioner static arm angle against a hand statics solve: the model laid out with one spring
// preload runs with a preload 6 N m stronger. The change of its static arm angle (belt and arm
// solved together) against the change the hand statics give for the same belt: the arm's
// moment balance M_s(θ) + T (c − p)×(d_out − d_in) = 0 with the tension of the stretched belt,
// T = EA (L_eff/L_belt − 1), where the belt line sinks into the penalty contact by
// p(T) − p(T0) on every wrap (k₂p² + k₁p = T/R, Ribaric (6.1)): L_eff = L_path(θ) −
// Σ φ_k (p_k(T) − p_k(T0)). Within 3 %. (The change, not the angle: the model's mounted state
// sits 0.67 mrad off the hand statics, see the frictionless test.) Without the contact's
// compliance the hand statics give a 20 % smaller change.
#[test]
fn tensioner_static_angle_matches_hand_statics() {
    let cfg = four_pulleys(0.0);
    let (mut belt, res) = flowing(&cfg, &four_pulleys_settings());
    let theta_m0 = belt.arm_angle(&belt.static_state().unwrap()).unwrap();
    belt.coords.tensioner.as_mut().unwrap().tensioner.preload -= 6.0;
    let theta_m = belt.arm_angle(&belt.static_state().unwrap()).unwrap();
    check_arm_change(&cfg, &res, theta_m0, theta_m, "flowing");
}

// The same for the rotating-mesh nodal model's tensioner (issue 17: the nodal belt on any
// layout, its arm with spring, preload and damper): the change of its static arm angle (belt,
// reference condition and arm solved together) against the hand statics, within 3 %.
#[test]
fn nodal_tensioner_static_angle_matches_hand_statics() {
    let cfg = four_pulleys(0.0);
    let (mut belt, res) = nodal(&cfg, &four_pulleys_settings());
    let theta_m0 = belt.arm_angle(&belt.static_state().unwrap()).unwrap();
    belt.coords.tensioner.as_mut().unwrap().tensioner.preload -= 6.0;
    let theta_m = belt.arm_angle(&belt.static_state().unwrap()).unwrap();
    check_arm_change(&cfg, &res, theta_m0, theta_m, "nodal");
}

/// The hand statics of the test above for the preload 6 N m stronger, against a model's arm
/// angles `theta_m0 → theta_m` before and after.
fn check_arm_change(cfg: &Layout, res: &belt::Drive, theta_m0: f64, theta_m: f64, model: &str) {
    use belt::BeltPath;
    use belt::layout::arm_lever;
    let theta_a = res.arm().unwrap().angle;
    let mut spec = cfg.tensioner.unwrap();
    spec.preload -= 6.0;
    let (k2, k1) = (cfg.contact.penalty_quadratic, cfg.contact.penalty_linear);
    let pen = |t: f64, r: f64| (-k1 + (k1 * k1 + 4.0 * k2 * t.max(0.0) / r).sqrt()) / (2.0 * k2);
    let (t0, ea, lb) = (res.tension(), cfg.belt.ea, res.belt_length());
    let (len, _) = spec.arm(cfg.pulleys[2].center);
    let tension_at = |theta: f64| -> (f64, f64) {
        let mut pp = cfg.pulleys.clone();
        pp[2].center = spec.center(len, theta).0;
        let path = BeltPath::new(&pp).unwrap();
        let mut t = t0;
        for _ in 0..100 {
            let sink: f64 = (0..4)
                .map(|k| {
                    path.wrap_angle(k).unwrap() * (pen(t, pp[k].radius) - pen(t0, pp[k].radius))
                })
                .sum();
            t = ea * ((path.length() - sink) / lb - 1.0);
        }
        (t, arm_lever(&path, &spec))
    };
    let theta_b = spec
        .static_angle(|th| {
            let (t, lever) = tension_at(th);
            t * lever
        })
        .unwrap();
    assert!(
        (theta_b - theta_a).abs() > 2e-3,
        "test needs the arm to move"
    );
    let err = ((theta_m - theta_m0) - (theta_b - theta_a)).abs() / (theta_b - theta_a).abs();
    eprintln!(
        "{model}: hand θ {theta_a:.5} → {theta_b:.5} (T {:.1} N), model {theta_m0:.5} → {theta_m:.5} rad; rel. err {err:.2e}",
        tension_at(theta_b).0
    );
    assert!(
        err < 0.03,
        "{model} model arm angle change off the hand statics by {:.1} %",
        100.0 * err
    );
}

/// Steady running of the four-pulley layout with `load` \[N m\] on each accessory: the mean
/// contact torque on every pulley over the last 0.2 s of 1 s, the crank's power and the
/// loads' power \[W\].
fn steady_power(load: f64) -> (Vec<f64>, f64, f64) {
    let cfg = four_pulleys(load);
    let (belt, _) = flowing(&cfg, &four_pulleys_settings());
    let q = belt.static_state().unwrap();
    let n = q.len();
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h: 2.5e-4,
        ..Default::default()
    });
    let mut acc = [0.0f64; 4];
    let mut count = 0usize;
    let mut p_in = 0.0;
    let mut p_out = 0.0;
    alpha
        .integrate(&belt, State::new(0.0, q, vec![0.0; n]), 1.0, |s| {
            if s.t > 0.8 {
                let tq = belt.pulley_torques(s.t, &s.q, &s.v);
                for k in 0..4 {
                    acc[k] += tq[k];
                }
                p_in += -tq[0] * belt.pulley_speed(0, s.t, &s.v);
                p_out += load * (belt.pulley_speed(1, s.t, &s.v) + belt.pulley_speed(3, s.t, &s.v));
                count += 1;
            }
        })
        .unwrap();
    let mean: Vec<f64> = acc.iter().map(|a| a / count as f64).collect();
    let (p_in, p_out) = (p_in / count as f64, p_out / count as f64);
    eprintln!(
        "load {load} N m: mean contact torques {mean:?} N m, P_in {p_in:.1} W, P_loads {p_out:.1} W, \
         loss {:.2} %",
        100.0 * (p_in - p_out) / p_in
    );
    (mean, p_in, p_out)
}

// Torque balance (issue 17 item 6) in a steady run at a light load (1 N m on each accessory,
// where the linearisation about T0 holds): each free accessory's
// contact torque equals its load, the idler carries none, and the crank puts in more power
// than the loads take, by the losses (belt hysteresis and creep: positive, below 2 %).
// Measured: crank 4.0087 N m against Σ τ_k R_crank/R_k = 4 N m, loss 0.48 %.
#[test]
fn steady_torques_balance_the_loads() {
    let (mean, p_in, p_out) = steady_power(1.0);
    for k in [1, 3] {
        assert!(
            (mean[k] - 1.0).abs() < 0.02,
            "pulley {k}: {} N m vs load 1",
            mean[k]
        );
    }
    assert!(mean[2].abs() < 0.05, "idler torque {}", mean[2]);
    let loss = (p_in - p_out) / p_in;
    assert!(loss > 0.0 && loss < 0.02, "loss fraction {loss}");
}

// The same at 4 N m per accessory fails: the crank gives 15.73 N m where 16 N m is needed,
// so the loads take 1.3 % more power than the crank puts in. Measured breakdown of the flow
// row at the end of the run: −e_tᵀKδ = +15.95 N against the tilt of the contact normal
// forces −12.0 N and friction −3.17 N; the b = T_,s z terms cancel (−11.41 vs +11.40 N), so
// projecting the flow row on e_t + b (tried) changes nothing. The defect grows faster than
// the load (+0.5 % loss at 1 N m, −0.9 % at 2 N m, −1.3 % at 4 N m): a second-order error
// of the model linearised about T0 (geometric stiffness K_g(T0) while the tight and slack
// spans carry T0 ± 107 N), cancelled by symmetry on a two-pulley drive. Not resolved: the
// nonlinear models carry the tension into their stiffness.
#[test]
#[ignore = "known limit (issue 17): the linearised flowing model on an unsymmetric layout at 4 N m creates 1.3 % power (second order in the load)"]
fn steady_torques_balance_the_loads_at_high_load() {
    let (mean, p_in, p_out) = steady_power(4.0);
    for k in [1, 3] {
        assert!(
            (mean[k] - 4.0).abs() < 0.08,
            "pulley {k}: {} N m vs load 4",
            mean[k]
        );
    }
    let loss = (p_in - p_out) / p_in;
    assert!(loss > 0.0 && loss < 0.05, "loss fraction {loss}");
}

// Bad input of issue 17: each rejected with the pulley or field named.
#[test]
fn bad_layouts_name_the_field() {
    let field = |c: &Layout| c.validate().unwrap_err().field;
    let mut c = four_pulleys(0.0);
    c.pulleys[3].center = [0.12, 0.25];
    assert_eq!(field(&c), "pulleys[3]");
    let mut c = four_pulleys(0.0);
    c.belt_length = Some(0.8);
    assert_eq!(field(&c), "belt_length");
    let mut c = four_pulleys(0.0);
    c.belt_length = Some(2.0);
    assert_eq!(field(&c), "belt_length");
    let mut c = four_pulleys(0.0);
    c.tensioner.as_mut().unwrap().preload = 400.0;
    assert_eq!(field(&c), "tensioner");
    // a back-side idler that deflects the alternator–pump span by 2 mm from outside: a wrap of
    // ≈ 2 (2 mm / 170 mm) rad ≈ 1.3°, below 10°
    let mut c = four_pulleys(0.0);
    c.tensioner = None;
    c.pulleys[2].motion = Motion::idler(1e-4);
    let three: Vec<_> = [0, 1, 3].iter().map(|&k| c.pulleys[k].clone()).collect();
    let span = belt::BeltPath::new(&three).unwrap().spans()[1];
    let r = c.pulleys[2].radius;
    // the loop runs clockwise: outside is to the left of the travel direction
    let out = [-span.direction[1], span.direction[0]];
    let off = r - 0.002;
    c.pulleys[2].center = [
        span.start[0] + 0.5 * span.length * span.direction[0] + off * out[0],
        span.start[1] + 0.5 * span.length * span.direction[1] + off * out[1],
    ];
    let e = c.validate().unwrap_err();
    assert!(e.field.starts_with("pulleys["), "{e}");
    assert!(
        e.reason.contains("wrap") || e.reason.contains("path"),
        "{e}"
    );
}

// The FEAD study on its defaults: every point completes; the accessories' contact torques
// balance their loads (steady mean over the window, within 3 %); the tensioner arm stays
// within its travel; a point flags `linearisation` exactly when a span's tension dips below
// 10 % of the installed tension. Up to 2500 rpm every span stays taut; at 3500 rpm the power
// steering → alternator span (≈ 108 Hz) meets the second firing order (116.7 Hz) and its
// tension swings from −88 to 619 N (measured 2026-11-26): the point is flagged.
#[test]
#[ignore = "heavy: the default engine-speed sweep (≈ 1 min in release on a loaded machine)"]
fn fead_default_sweep_runs() {
    let cfg = drives::fead::FeadConfig::default();
    let t = std::time::Instant::now();
    let s = drives::fead::run_fead(&cfg, |_| {}).unwrap();
    eprintln!(
        "{} steps, {} dofs, {:.1} s",
        s.steps,
        s.dofs,
        t.elapsed().as_secs_f64()
    );
    let travel = s.arm_travel.unwrap();
    for p in &s.points {
        eprintln!(
            "{} rpm: v {:.2} m/s arm {:.4}..{:.4} rad; spans {:?}; slip {:?}; torques {:?}; f1 {:?}",
            p.engine_rpm,
            p.belt_speed,
            p.arm_angle.expect("the layout has a tensioner").min,
            p.arm_angle.expect("the layout has a tensioner").max,
            p.spans
                .iter()
                .map(|x| (x.tension.min.round(), x.tension.max.round()))
                .collect::<Vec<_>>(),
            p.speed_loss_percent
                .iter()
                .map(|x| (x * 100.0).round() / 100.0)
                .collect::<Vec<_>>(),
            p.report
                .pulleys
                .iter()
                .map(|x| (x.torque_n_m * 100.0).round() / 100.0)
                .collect::<Vec<_>>(),
            p.spans
                .iter()
                .map(|x| x.frequency_1_hz.map(f64::round))
                .collect::<Vec<_>>(),
        );
        assert!(
            p.arm_angle.expect("the layout has a tensioner").min > travel[0]
                && p.arm_angle.expect("the layout has a tensioner").max < travel[1]
        );
        // every span taut, or the point says it left the linearised model's range
        let t_min = drives::speed_loss::LINEAR_MIN_SLACK * s.installed_tension;
        let slack = p.spans.iter().any(|sp| sp.tension.min < t_min);
        assert_eq!(
            slack,
            p.linearisation.is_some(),
            "{} rpm: spans {:?}, flag {:?}",
            p.engine_rpm,
            p.spans.iter().map(|sp| sp.tension.min).collect::<Vec<_>>(),
            p.linearisation
        );
        if p.engine_rpm <= 2500.0 {
            assert!(!slack, "{} rpm: a span goes slack", p.engine_rpm);
        }
        // J ω̇ = τ − M: over a window that is not a whole number of fluctuation periods the
        // mean of τ − M is bounded by J (ω_max − ω_min)/window
        for (k, load, j) in [
            (1, 2.0, 1e-3),
            (2, 3.0, 3e-3),
            (4, 1.5, 8e-4),
            (5, 5.0, 2e-3),
        ] {
            let pl = &p.report.pulleys[k];
            let w = &p.pulley_speed[k];
            let bound = j * (w.max - w.min) / cfg.run.window + 0.02 * load;
            assert!(
                (pl.torque_n_m - load).abs() < bound,
                "{} rpm, {}: {} vs {load} ± {bound}",
                p.engine_rpm,
                pl.name,
                pl.torque_n_m
            );
        }
    }
}

/// Lowest transverse natural frequency \[Hz\] of span `k` of the linearised layout model at the
/// state `(q, v)`, and the computed tension of that span \[N\]: the damped frequencies of the
/// model's tangent (`M`, `C_t`, `K_t`), each mode's share of transverse deflection on the
/// span's interior nodes (the lowest mode with more than half its transverse motion there).
fn span_mode(belt: &flowing::belt::FlowingBelt, k: usize, q: &[f64], v: &[f64]) -> (f64, f64) {
    use mbd_core::{SysMatrix, Workspace};
    let t = 1.0;
    let dense = |m: SysMatrix| match m {
        SysMatrix::Dense(m) => m,
        SysMatrix::Sparse(s) => s.to_dense(),
    };
    let mass = dense(belt.mass(t, q).unwrap());
    let tan = belt
        .force_tangent(t, q, v, &mut Workspace::new())
        .unwrap()
        .unwrap();
    let mass_diag: Vec<f64> = (0..mass.nrows()).map(|i| mass[(i, i)]).collect();
    let sys =
        flowing::GyroscopicSystem::new(mass, dense(tan.damping), dense(tan.stiffness)).unwrap();
    let eig = sys.state_eigen().unwrap();
    let n = sys.dim();
    let m = belt.n_modes();
    let span = belt.fe.path().spans()[k];
    let normal = [-span.direction[1], span.direction[0]];
    // interior nodes of the span (not its end points on the pulleys)
    let piece = belt
        .fe
        .path()
        .pieces()
        .iter()
        .find(|p| matches!(p.segment, belt::Segment::Span { from, .. } if from == k))
        .copied()
        .unwrap();
    let on_span: Vec<usize> = (0..belt.fe.n_nodes())
        .filter(|&i| {
            let x = belt.fe.s[i] - piece.s_start;
            x > 1e-9 && x < piece.length - 1e-9
        })
        .collect();
    assert!(
        on_span.len() >= 4,
        "span {k} has {} interior nodes",
        on_span.len()
    );
    let mut best: Option<f64> = None;
    for (j, lam) in eig.values.iter().enumerate() {
        if lam.im <= 1e-6 {
            continue;
        }
        let f = lam.im / (2.0 * std::f64::consts::PI);
        // nodal deflection of the mode (real and imaginary parts of δ = T z)
        let part = |re: bool| {
            let z: Vec<f64> = (1..=m)
                .map(|i| {
                    let c = eig.vectors[(i, j)];
                    if re { c.re } else { c.im }
                })
                .collect();
            belt.deflection(&z)
        };
        let (dr, di) = (part(true), part(false));
        let transverse = |i: usize| {
            let a = dr[3 * i] * normal[0] + dr[3 * i + 1] * normal[1];
            let b = di[3 * i] * normal[0] + di[3 * i + 1] * normal[1];
            a * a + b * b
        };
        // mass-weighted: the belt's deflection, its travel and the pulleys' spins
        let mi = |i: usize| belt.fe.mass[3 * i];
        let rigid: f64 = std::iter::once(0)
            .chain(m + 1..n)
            .map(|c| {
                let x = eig.vectors[(c, j)];
                mass_diag[c] * (x.re * x.re + x.im * x.im)
            })
            .sum();
        let total: f64 = rigid
            + (0..belt.fe.n_nodes())
                .map(|i| {
                    mi(i)
                        * (dr[3 * i].powi(2)
                            + dr[3 * i + 1].powi(2)
                            + di[3 * i].powi(2)
                            + di[3 * i + 1].powi(2))
                })
                .sum::<f64>();
        let share = on_span.iter().map(|&i| mi(i) * transverse(i)).sum::<f64>() / total;
        // a vibration mode, not one of the creep modes the friction law's slope damps out
        let zeta = -lam.re / lam.re.hypot(lam.im);
        if share > 0.5 && zeta < 0.3 && best.is_none_or(|b| f < b) {
            best = Some(f);
        }
    }
    let snap = belt.snapshot(t, q, v).unwrap();
    let tension = snap.spans.iter().find(|s| s.from == k).unwrap().tension;
    (best.expect("no transverse mode of the span"), tension)
}

// A span's transverse natural frequency (issue 17 item 6) against the travelling-string
// formula with the computed span tension, f₁ = (1 − v²/c²) c / (2 l), c = √(T/m) (the axially
// moving string, Ribaric ch. 4 / Wickert & Mote 1990; the formula `drives::fead` plots on its
// Campbell diagram), on the four-pulley layout without its tensioner, span 0 (crank →
// alternator, l = 0.301 m).
// 1. At rest with the bending stiffness cut a hundredfold (a string): the model's span mode
//    within 1 % of the formula with the computed span tension.
// 2. At rest with the belt's own EI: between the tensioned beam with pinned ends,
//    f_s √(1 + π² ε²), and with clamped ends, f_s (1 + 2ε + (4 + π²/2) ε²), ε = √(EI/(T l²))
//    (the belt leaves the pulleys tangentially: neither pinned nor fully clamped).
// 3. Running at 6 m/s: the linear model keeps the geometric stiffness K_g(T0) of the mounted
//    belt (Ribaric ch. 5), so its span frequency follows the travelling-string formula with
//    the tension it was linearised at, f(v)/f(0) = 1 − v²/c₀², within 0.1 %. The span tension
//    the model computes rises by ≈ m v² (the centrifugal tension of a fixed-centre drive);
//    a model that carried it into the stiffness would raise the frequency by a further
//    ½ ΔT/T ≈ 0.7 % at this speed: printed, the linearisation's known limit.
#[test]
fn span_transverse_frequency_is_the_travelling_string_one() {
    let build = |ei_scale: f64| {
        let mut cfg = four_pulleys(0.0);
        cfg.tensioner = None;
        cfg.belt.ei *= ei_scale;
        let (belt, drive) = flowing(&cfg, &four_pulleys_settings());
        (cfg, drive, belt)
    };
    let k = 0;
    // 1. the string limit
    let (cfg, drive, belt) = build(0.01);
    let mass = cfg.belt.mass_per_length;
    let l = belt.fe.path().spans()[k].length;
    let string = |t: f64, v: f64| {
        let c = (t / mass).sqrt();
        (1.0 - v * v / (c * c)) * c / (2.0 * l)
    };
    let q0 = belt.static_state().unwrap();
    let n = q0.len();
    let (f_rest, t_rest) = span_mode(&belt, k, &q0, &vec![0.0; n]);
    eprintln!(
        "string limit at rest: l = {l:.4} m, T = {t_rest:.2} N, model {f_rest:.3} Hz, formula {:.3} Hz",
        string(t_rest, 0.0)
    );
    assert!(
        (f_rest / string(t_rest, 0.0) - 1.0).abs() < 0.01,
        "at rest: model {f_rest} Hz vs string {} Hz",
        string(t_rest, 0.0)
    );
    // 3. running at the crank's 80 rad/s (its ramp ends at 0.1 s)
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h: 2.5e-4,
        ..Default::default()
    });
    let mut last = None;
    alpha
        .integrate(&belt, State::new(0.0, q0.clone(), vec![0.0; n]), 0.5, |s| {
            last = Some(s.clone());
        })
        .unwrap();
    let s = last.unwrap();
    let speed = s.v[0];
    let (f_run, t_run) = span_mode(&belt, k, &s.q, &s.v);
    let t0 = drive.tension();
    let ratio_model = f_run / f_rest;
    let ratio_t0 = string(t0, speed) / string(t0, 0.0);
    eprintln!(
        "running at {speed:.3} m/s: T = {t_run:.2} N (T0 = {t0} N), model {f_run:.3} Hz; \
         f(v)/f(0): model {ratio_model:.5}, string at T0 {ratio_t0:.5}, string at the computed \
         tension {:.5}",
        string(t_run, speed) / string(t_rest, 0.0)
    );
    assert!(
        (ratio_model / ratio_t0 - 1.0).abs() < 1e-3,
        "f(v)/f(0): model {ratio_model} vs travelling string at T0 {ratio_t0}"
    );
    // 2. the belt's own bending stiffness
    let (cfg, _, belt) = build(1.0);
    let q0 = belt.static_state().unwrap();
    let (f_beam, t) = span_mode(&belt, k, &q0, &vec![0.0; n]);
    let eps = (cfg.belt.ei / (t * l * l)).sqrt();
    let pi2 = std::f64::consts::PI.powi(2);
    let pinned = string(t, 0.0) * (1.0 + pi2 * eps * eps).sqrt();
    let clamped = string(t, 0.0) * (1.0 + 2.0 * eps + (4.0 + 0.5 * pi2) * eps * eps);
    eprintln!(
        "EI = {} N m²: model {f_beam:.3} Hz, pinned beam {pinned:.3} Hz, clamped beam {clamped:.3} Hz",
        cfg.belt.ei
    );
    assert!(
        f_beam > pinned && f_beam < clamped,
        "model {f_beam} Hz outside [{pinned}, {clamped}] Hz"
    );
}

// A sweep restarts time at every engine speed: the crank speed signal of the next point
// carries the previous point's orders on (phases continued, faded out over the ramp), so the
// crank speed and its rate are continuous across the restart (reference: the previous point's
// signal at its end time). Before, the orders' sum (2 % of the speed) jumped to zero and the
// default flowing sweep failed to converge at the second speed.
#[test]
fn fead_sweep_crank_signal_is_continuous_across_points() {
    use drives::fead::{FeadConfig, crank_signal, run_fead};
    let c = FeadConfig::default();
    let (w1, w2, ramp) = (
        800.0 * std::f64::consts::PI / 30.0,
        1500.0 * std::f64::consts::PI / 30.0,
        c.run.ramp,
    );
    let first = crank_signal(&c.engine, 0.0, w1, ramp, None);
    let t_end = 1.2345;
    let next = crank_signal(&c.engine, w1, w2, ramp, Some(t_end));
    let (a, b) = (first.eval(t_end), next.eval(0.0));
    assert!((a.0 - b.0).abs() < 1e-9 * w1, "speed {a:?} vs {b:?}");
    assert!((a.1 - b.1).abs() < 1e-7 * w1 * w1, "rate {a:?} vs {b:?}");
    // after the ramp only the new orders remain: the signal of a fresh start at the same time
    let fresh = crank_signal(&c.engine, w1, w2, ramp, None);
    let t = ramp + 0.01;
    assert!((next.value(t) - fresh.value(t)).abs() < 1e-9 * w2);
    // the default flowing sweep over two speeds runs (it failed at the second)
    let mut two = FeadConfig::default();
    two.engine.speeds_rpm = vec![800.0, 1500.0];
    let s = run_fead(&two, |_| {}).unwrap_or_else(|e| panic!("{e:?}"));
    assert_eq!(s.points.len(), 2);
}
