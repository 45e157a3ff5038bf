//! Sub-stepping through the cleat impact (`RigConfig::impact`, `RollingTire::set_time_step`)
//! and the cleat's position along the ground (`Ground::cleat_ahead`).

use tire::*;

use crate::common;
use common::{coarse_reduced_tire as tire, rig};

/// The cleat rig on the drum (μ = 0.85) without sub-steps, settling for `t` and recording `t`
/// \[s\].
fn plain_rig(t: f64) -> RigConfig {
    let mut rc = rig(GroundKind::Drum, true, 0.85);
    rc.settle_time = t;
    rc.record_time = t;
    rc.impact.substeps = 1;
    rc
}

#[test]
fn cleat_position_along_drum_and_road() {
    // Analytical: the cleat moves with the surface speed; on the drum it comes round every
    // 2πR/v and the nearest passage is reported.
    let mut g = Ground::new(GroundConfig::default(), -0.5, 10.0, 0.0, 0.3).unwrap();
    let period = 2.0 * std::f64::consts::PI * 1.25 / 10.0;
    for (t, want) in [(0.3, 0.0), (0.29, 0.1), (0.31, -0.1), (0.3 + period, 0.0)] {
        let d = g.cleat_ahead(t).unwrap();
        assert!(
            (d - want).abs() < 1e-12,
            "drum t = {t}: {d} m, want {want} m"
        );
    }
    g.cfg.kind = GroundKind::Road;
    assert!((g.cleat_ahead(0.3 - period).unwrap() - 10.0 * period).abs() < 1e-12);
    g.cfg.cleat = false;
    assert_eq!(g.cleat_ahead(0.3), None);
}

#[test]
fn substeps_over_the_whole_run_equal_the_small_step() {
    // Second formulation: a window covering the whole run with n sub-steps is the run at h/n,
    // sampled every n-th step, operation for operation.
    let red = tire();
    let mut fine = plain_rig(0.02);
    let mut coarse = fine.clone();
    coarse.impact = ImpactConfig {
        substeps: 4,
        lead: 10.0,
        trail: 10.0,
    };
    fine.rolling.time_step = coarse.rolling.time_step / 4.0;
    let a = run_cleat(red, &coarse, &mut |_| {}).unwrap();
    let b = run_cleat(red, &fine, &mut |_| {}).unwrap();
    assert_eq!(a.samples.len() * 4, b.samples.len());
    assert!(
        a.samples.iter().any(|s| s.cleat_nodes > 0),
        "the cleat is hit"
    );
    for (k, s) in a.samples.iter().enumerate() {
        let f = &b.samples[4 * k + 3];
        assert!((s.t - f.t).abs() < 1e-12);
        assert_eq!((s.fy, s.fx, s.spin), (f.fy, f.fx, f.spin), "sample {k}");
    }
}

#[test]
fn substeps_are_used_only_around_the_cleat() {
    // The window: the cleat within `lead` ahead of the patch centre until `trail` after it
    // passed. Outside it the run is the plain one step for step (same samples before the
    // window); the sub-steps show in the step count.
    let red = tire();
    let plain = plain_rig(0.03);
    let mut sub = plain.clone();
    sub.impact = ImpactConfig {
        substeps: 4,
        // off the step grid (0.1 m / v and 0.01 s are whole steps), so no step starts on an edge
        lead: 0.1003,
        trail: 0.0101,
    };
    let a = run_cleat(red, &plain, &mut |_| {}).unwrap();
    let b = run_cleat(red, &sub, &mut |_| {}).unwrap();
    assert_eq!(a.samples.len(), b.samples.len());
    let v = plain.speed_kmh / 3.6;
    let h = plain.rolling.time_step;
    // window in time: from lead/v before the cleat reaches the centre to trail after
    let (t0, t1) = (-sub.impact.lead / v, sub.impact.trail);
    let inside = a
        .samples
        .iter()
        .filter(|s| s.t - h >= t0 && s.t - h <= t1)
        .count();
    assert_eq!(b.stats.steps, a.stats.steps + 3 * inside);
    for (s, f) in a.samples.iter().zip(&b.samples) {
        if s.t - h < t0 {
            assert_eq!(
                (s.fy, s.fx),
                (f.fy, f.fx),
                "before the window at t = {}",
                s.t
            );
        }
    }
    let bad = RigConfig {
        impact: ImpactConfig {
            substeps: 0,
            ..Default::default()
        },
        ..plain
    };
    let e = run_cleat(red, &bad, &mut |_| {}).unwrap_err().to_string();
    assert!(e.contains("impact.substeps"), "{e}");
}

#[test]
fn a_cleat_phase_only_delays_the_cleat() {
    // `RigConfig::with_cleat_phase`: the settle time grows by the fraction of an impact step;
    // the tire rolls step for step as before (same forces) until the cleat comes near, and the
    // samples' t = 0 stays at the cleat hit (invariant of the rig's time axis).
    let red = tire();
    let mut base = plain_rig(0.02);
    base.impact.substeps = 4;
    let shifted = base.with_cleat_phase(0.5);
    let dt = 0.5 * base.rolling.time_step / 4.0;
    assert!((base.impact_step() - base.rolling.time_step / 4.0).abs() < 1e-18);
    assert!((shifted.settle_time - base.settle_time - dt).abs() < 1e-15);
    let a = run_cleat(red, &base, &mut |_| {}).unwrap();
    let b = run_cleat(red, &shifted, &mut |_| {}).unwrap();
    let v = base.speed_kmh / 3.6;
    let before = |s: &Sample| s.t < -(base.impact.lead + 0.02) / v;
    let n = a.samples.iter().filter(|s| before(s)).count();
    assert!(n > 10, "{n} samples before the cleat");
    for (s, f) in a.samples.iter().zip(&b.samples).take(n) {
        assert_eq!((s.fy, s.fx, s.spin), (f.fy, f.fx, f.spin));
        assert!((s.t - f.t - dt).abs() < 1e-12, "t = {} vs {}", s.t, f.t);
    }
    // after the hit the phase matters: the histories differ
    assert!(
        a.samples
            .iter()
            .zip(&b.samples)
            .any(|(s, f)| s.cleat_nodes > 0 && (s.fy - f.fy).abs() > 1.0),
        "the cleat phase changes the impact"
    );
}

#[test]
fn phase_spread_is_the_mean_and_sample_deviation() {
    // `PhaseSpread::of` against the textbook formulas on three runs whose summaries differ
    // only in the line amplitudes (analytical: mean 2, sample sd 1 of {1, 2, 3}).
    let red = tire();
    let r = run_cleat(red, &plain_rig(0.01), &mut |_| {}).unwrap();
    let mut s: Vec<CleatSummary> = (0..3).map(|_| summarize(&r)).collect();
    for (k, x) in s.iter_mut().enumerate() {
        x.fy_band_rms_n = 1.0 + k as f64;
        x.fx_band_rms_n = 10.0 * (1.0 + k as f64);
    }
    let p = PhaseSpread::of(&s.iter().collect::<Vec<_>>());
    assert_eq!(p.phases, 3);
    assert!((p.fy_band_rms_mean_n - 2.0).abs() < 1e-15);
    assert!((p.fy_band_rms_sd_n - 1.0).abs() < 1e-15);
    assert!((p.fx_band_rms_mean_n - 20.0).abs() < 1e-13);
    assert!((p.fx_band_rms_sd_n - 10.0).abs() < 1e-13);
    assert_eq!(p.fy_band_rms_n, vec![1.0, 2.0, 3.0]);
    let one = PhaseSpread::of(&[&s[0]]);
    assert_eq!(one.fy_band_rms_sd_n, 0.0);
}
