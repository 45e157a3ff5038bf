//! Wall time per simulated second of the three-dimensional plate-belt drive (Kerkkänen §4.6,
//! issue 18) against the planar ANCF belt drive (Kerkkänen ch. 3) on the same case:
//!
//! - Model 2 in steady operation (driver 500 rad/s, 2 N·m, belt started at the driver's surface
//!   speed), generalized-α `h = 5·10⁻⁵ s` (the study's step);
//! - Model 1 during the start (centre shift (4.46), ramp (3.29)), `h = 10⁻⁴ s`;
//! - the wide-pulley case (`drives::plate_study::wide_pulley_case`: Model 2's geometry, contact
//!   and section, k = 2 kN, 50 N pre-tension, ramp to 100 rad/s, 0.5 N·m) with the plate belt and
//!   with its planar equivalent (`PlateDriveSpec::planar_equivalent`: per-length contact =
//!   per-area × width), both at `h = 10⁻⁴ s`, run alternately so that both see the same load;
//!   `ratio = plate / planar`.
//!
//! The planar drive cannot take Model 2 itself (its belt is 20 % shorter than the path; the
//! planar drive accepts 10 %), hence the wide-pulley case as the common ground.
//! Run: `cargo bench -p drives --bench plate_belt` (about two minutes on a free core).

use ancf::belt_drive::{BeltDrive, InitialOptions};
use ancf::plate::belt_drive::{PlateBeltDrive, PlateDriveSpec};
use belt::{Motion, Signal};
use drives::ancf_run::{Sampling, run_drive};
use drives::plate_study::{PlateStudyConfig, plate_setup, wide_pulley_case};
use mbd_core::SecondOrderSystem;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, State, Stepper};
use std::time::Instant;

fn alpha(h: f64) -> AlphaConfig {
    AlphaConfig {
        rho_inf: 0.6,
        h,
        newton_atol: 1e-7,
        max_newton_iterations: 25,
        max_halvings: 10,
        ..AlphaConfig::default()
    }
}

/// Wall seconds per simulated second of `sys` from `s0` over `t` \[s\], with the steps and
/// Newton iterations.
fn timed<S: SecondOrderSystem>(sys: &S, s0: State, t: f64, h: f64) -> (f64, usize, usize) {
    let start = Instant::now();
    let mut st = GeneralizedAlpha::new(alpha(h))
        .stepper(sys, s0)
        .expect("initial state");
    let t_end = st.state().t + t;
    st.advance_to(sys, t_end, &mut ()).expect("run");
    (
        start.elapsed().as_secs_f64() / t,
        st.stats.steps,
        st.stats.newton_iterations,
    )
}

fn main() {
    // Model 2, steady operation
    let mut spec = PlateDriveSpec::kerkkanen_model2();
    spec.pulleys[0].motion = Motion::speed(Signal::constant(500.0));
    spec.pulleys[1].motion = Motion::load(0.00025, Signal::constant(2.0));
    let d = PlateBeltDrive::new(spec).expect("Model 2");
    let init = d
        .initial_state(&InitialOptions::default())
        .expect("initial state");
    let v = d.travelling_velocity(&init.q, 25.0);
    let (w, steps, it) = timed(&d, State::new(0.0, init.q.clone(), v), 0.02, 5e-5);
    println!(
        "Model 2 (360 + 1 coordinates), steady 500 rad/s: {w:.1} s per simulated second ({steps} steps, {it} Newton iterations in 0.02 s)"
    );

    // Model 2 as the study runs it (defaults: belt at rest, driver ramped from 0), first
    // 0.02 s: Newton iterations per step. 1.21 at b350b63; the band-LU cut plan without the
    // backward-error check (6bd31ba .. 63e148c) took 4.6, and 9.6 over 0.2 s (issue 37).
    let c = PlateStudyConfig::default();
    let (drive, init) = plate_setup(&c).expect("Model 2 study setup");
    let start = Instant::now();
    let sampling = Sampling {
        history: 1e-3,
        frame: 1.0,
    };
    let run = run_drive(&drive, &init.q, 0.02, &c.integrator, sampling, |_, _| {
        Ok::<(), ()>(())
    })
    .expect("run");
    assert!(run.failure.is_none(), "{:?}", run.failure);
    let w = start.elapsed().as_secs_f64() / 0.02;
    println!(
        "Model 2 study defaults, 0-0.02 s: {w:.1} s per simulated second, {:.2} Newton iterations per step ({} steps; 1.21 at b350b63, 4.6 with the unchecked cut plan)",
        run.stats.newton_iterations as f64 / run.stats.steps.max(1) as f64,
        run.stats.steps
    );

    // Model 1, start
    let d = PlateBeltDrive::new(PlateDriveSpec::kerkkanen_model1()).expect("Model 1");
    let init = d
        .initial_state(&InitialOptions::default())
        .expect("initial state");
    let s0 = State::new(0.0, init.q.clone(), vec![0.0; d.n_q()]);
    let (w, steps, it) = timed(&d, s0, 0.1, 1e-4);
    println!(
        "Model 1 (288 + 1 coordinates), start 0–0.1 s: {w:.1} s per simulated second ({steps} steps, {it} Newton iterations)"
    );

    // wide-pulley case, plate vs planar, alternately
    let p = wide_pulley_case(100.0, 0.5);
    let planar = p
        .planar_equivalent(0.01)
        .expect("no crown, flanges or shift");
    let d3 = PlateBeltDrive::new(p).expect("plate");
    let i3 = d3
        .initial_state(&InitialOptions::default())
        .expect("initial state");
    let d2 = BeltDrive::new(planar).expect("planar");
    let i2 = d2
        .initial_state(&InitialOptions::default())
        .expect("initial state");
    let mut ratios = Vec::new();
    for round in 0..2 {
        let (w3, n3, it3) = timed(
            &d3,
            State::new(0.0, i3.q.clone(), vec![0.0; d3.n_q()]),
            0.1,
            1e-4,
        );
        let (w2, n2, it2) = timed(
            &d2,
            State::new(0.0, i2.q.clone(), vec![0.0; d2.n_q()]),
            0.1,
            1e-4,
        );
        println!(
            "wide case, round {round}: plate {w3:.2} s/s ({n3} steps, {it3} it.), planar {w2:.2} s/s ({n2} steps, {it2} it.)"
        );
        ratios.push(w3 / w2);
    }
    let best = ratios.iter().cloned().fold(f64::INFINITY, f64::min);
    println!(
        "ratio = plate / planar = {best:.2} (best of {} rounds)",
        ratios.len()
    );
}
