//! The FEAD study's crank speed trace (issue 36 item 5, `drives::crank_trace`) and its
//! decoupler outputs and refusals (item 4).
//!
//! References: a trace of `ω̄ (1 + a sin(2 ω̄ t))` sampled in time, or in crank angle with the
//! exact `θ(t) = ω̄ t + (a/2)(1 − cos 2ω̄t)`, gives the crank speed history of the equivalent
//! engine-order (`harmonics`) signal (second formulation) within the linear interpolation's
//! error `ω̄ a (2ω̄)² Δt²/8`.

use belt::{Decoupler, Motion};
use drives::crank_trace::{Abscissa, CrankTrace};
use drives::fead::{
    CrankPoint, EngineOrder, FeadConfig, FeadFailureOrInvalid, FeadModel, crank_points, run_fead,
};
use std::f64::consts::PI;
use std::path::PathBuf;

const RPM: f64 = 1500.0;
const A: f64 = 0.02;

fn tmp(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flowmbd-crank-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn w_bar() -> f64 {
    RPM * PI / 30.0
}

fn omega(t: f64) -> f64 {
    w_bar() * (1.0 + A * (2.0 * w_bar() * t).sin())
}

/// The orders configuration: order 2 at `A`, its phase shifted by the ramp (the trace starts
/// after the ramp).
fn harmonic_config() -> FeadConfig {
    let mut c = FeadConfig::default();
    c.engine.speeds_rpm = vec![RPM];
    c.engine.orders = vec![EngineOrder {
        order: 2.0,
        amplitude: A,
        phase: -2.0 * w_bar() * c.run.ramp,
    }];
    c
}

fn trace_config(file: PathBuf, abscissa: Abscissa) -> FeadConfig {
    let mut c = harmonic_config();
    c.engine.speeds_rpm = vec![1.0];
    c.engine.orders.clear();
    c.engine.trace = Some(CrankTrace {
        file,
        abscissa,
        periodic: true,
    });
    c
}

fn points(c: &FeadConfig) -> CrankPoint {
    let mut p = crank_points(c, c.run.step).unwrap();
    assert_eq!(p.len(), 1);
    p.remove(0)
}

/// Largest speed difference \[rad/s\] after the ramp over the whole run.
fn compare(a: &CrankPoint, b: &CrankPoint, c: &FeadConfig) -> f64 {
    let (t0, t1) = (c.run.ramp, c.run.ramp + c.run.max_settle + a.window.0);
    (0..=20_000)
        .map(|i| t0 + (t1 - t0) * i as f64 / 20_000.0)
        .map(|t| (a.signal.value(t) - b.signal.value(t)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn time_trace_matches_the_engine_order_signal() {
    let period = PI / w_bar();
    let n = 400;
    let mut csv = String::from("# constant speed plus 2nd order\ntime_s, speed_rad_per_s\n");
    for i in 0..=n {
        let t = period * i as f64 / n as f64;
        csv.push_str(&format!("{t:.17e}, {:.17e}\n", omega(t)));
    }
    let c = trace_config(tmp("time.csv", &csv), Abscissa::Time);
    let (tr, h) = (points(&c), points(&harmonic_config()));
    assert!(
        (tr.rpm - RPM).abs() < 1e-9 * RPM,
        "trace mean {} rpm",
        tr.rpm
    );
    assert_eq!(tr.window, h.window, "whole periods of order 2 either way");
    let dt = period / n as f64;
    let bound = w_bar() * A * (2.0 * w_bar()).powi(2) * dt * dt / 8.0;
    let err = compare(&tr, &h, &c);
    assert!(err <= 1.01 * bound + 1e-9, "{err} vs {bound} rad/s");
}

#[test]
fn angle_trace_matches_the_engine_order_signal() {
    // one period of order 2 is π rad of crank angle; samples every 0.25°
    let n = 720;
    let theta = |t: f64| w_bar() * t + 0.5 * A * (1.0 - (2.0 * w_bar() * t).cos());
    let mut csv = String::from("angle_rad,speed_rad_per_s\n");
    let mut t = 0.0;
    for i in 0..=n {
        let th = PI * i as f64 / n as f64;
        for _ in 0..50 {
            t -= (theta(t) - th) / omega(t);
        }
        csv.push_str(&format!("{th:.17e},{:.17e}\n", omega(t)));
    }
    let c = trace_config(tmp("angle.csv", &csv), Abscissa::Angle);
    let (tr, h) = (points(&c), points(&harmonic_config()));
    // the period from the angle trace: ∫ dθ/ω over π rad
    assert!(
        (tr.window.0 - h.window.0).abs() < 1e-9,
        "{:?} vs {:?}",
        tr.window,
        h.window
    );
    let dt = PI / w_bar() / n as f64;
    let bound = w_bar() * A * (2.0 * w_bar()).powi(2) * dt * dt / 8.0;
    let err = compare(&tr, &h, &c);
    assert!(err <= 1.5 * bound, "{err} vs {bound} rad/s");
}

fn invalid(c: &FeadConfig) -> mbd_core::InvalidField {
    match *run_fead(c, |_| {}).unwrap_err() {
        FeadFailureOrInvalid::Invalid(f) => f,
        e => panic!("expected an input error, got {e}"),
    }
}

#[test]
fn malformed_traces_are_input_errors_naming_file_and_line() {
    for (name, text, line) in [
        ("bad-number.csv", "t,w\n0,100\n0.01,abc\n", Some(3)),
        ("bad-columns.csv", "0,100\n0.01\n", Some(2)),
        ("bad-order.csv", "0,100\n0.01,101\n0.005,99\n", Some(3)),
        ("empty.csv", "# nothing\n", None),
    ] {
        let p = tmp(name, text);
        let f = invalid(&trace_config(p.clone(), Abscissa::Time));
        assert_eq!(f.field, "engine.trace.file");
        let at = match line {
            Some(l) => format!("{}:{l}: ", p.display()),
            None => format!("{}: ", p.display()),
        };
        assert!(f.reason.starts_with(&at), "{name}: {}", f.reason);
    }
    // not a regular file, missing, too large (16 MiB + 1 byte)
    let dir = tmp("x.csv", "").parent().unwrap().to_path_buf();
    let f = invalid(&trace_config(dir, Abscissa::Time));
    assert!(f.reason.contains("not a regular file"), "{}", f.reason);
    let f = invalid(&trace_config(
        "/nonexistent/crank.csv".into(),
        Abscissa::Time,
    ));
    assert!(f.reason.contains("cannot read"), "{}", f.reason);
    let big = tmp("big.csv", &"0".repeat(16 * 1024 * 1024 + 1));
    let f = invalid(&trace_config(big.clone(), Abscissa::Time));
    assert!(f.reason.contains("more than the"), "{}", f.reason);
    std::fs::remove_file(big).unwrap();
}

fn decoupled_alternator(c: &mut FeadConfig) {
    if let Motion::Load { decoupler, .. } = &mut c.drive.pulleys[2].motion {
        *decoupler = Some(Decoupler {
            pulley_inertia: 3e-4,
            stiffness: 30.0,
            damping: 0.2,
            clutch: true,
            carrier_inertia: 2e-5,
            lock_damping: 1000.0,
            lock_speed: 1e-3,
        });
    }
}

// The ANCF belt has no decoupler coordinates: the study refuses the input, naming the field.
#[test]
fn ancf_refuses_a_decoupler() {
    let mut c = FeadConfig::default();
    decoupled_alternator(&mut c);
    c.model = FeadModel::Ancf;
    let f = invalid(&c);
    assert!(
        f.field.contains("pulleys[2].motion.decoupler") && f.reason.contains("flowing or nodal"),
        "{f}"
    );
    let d = c.drive.resolve().unwrap();
    let e = ancf::plate::belt_drive::belt_model::plate_spec(&d, &Default::default()).unwrap_err();
    assert!(e.to_string().contains("pulleys[2].motion.decoupler"), "{e}");
}

// A short FEAD point with a decoupled alternator on the flowing belt: the summary carries the
// decoupler's window; steady, the accessory's mean speed is the pulley's and the spring's mean
// torque the alternator's 3 N m load (torque balance of (D3) over a period), with a smaller
// speed fluctuation than the pulley's (isolation).
#[test]
fn fead_reports_the_decoupler() {
    let mut c = FeadConfig::default();
    decoupled_alternator(&mut c);
    c.engine.speeds_rpm = vec![1500.0];
    c.run.ramp = 0.1;
    c.run.settle = 0.1;
    c.run.max_settle = 0.4;
    c.run.window = 0.02;
    let s = run_fead(&c, |_| {}).unwrap();
    let p = &s.points[0];
    let d = &p.decouplers[0];
    assert_eq!(d.pulley, "alternator");
    let wp = p.pulley_speed[2].mean;
    assert!(
        (d.accessory_speed.mean - wp).abs() < 0.01 * wp,
        "{} vs {wp}",
        d.accessory_speed.mean
    );
    assert!(p.steady);
    // steady: the spring carries the alternator's 3 N m on average
    assert!(
        (d.spring_torque.mean - 3.0).abs() < 0.1,
        "{:?}",
        d.spring_torque
    );
    // the decoupler isolates the accessory from the crank's fluctuation
    let range = |e: &drives::fead::Extremes| e.max - e.min;
    assert!(range(&d.accessory_speed) < 0.5 * range(&p.pulley_speed[2]));
    assert!(d.overrunning_fraction.is_some() && d.clutch_at_end.is_some());
}
