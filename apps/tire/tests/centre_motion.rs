//! The prescribed wheel-centre motion of the rig, `[rig.wheel.centre_motion]` (issue 38 items 1
//! and 4: the tire FMU's inputs as time series, run by `flowmbd-tire cleat` through the FMU's
//! engine `tire::motion::CoSimulation`), on the small tire of `common`: the configuration is
//! read and refused with the field named, a run writes one `forces.csv` row per communication
//! step, and a constant prescribed motion reproduces the rig's fixed wheel centre.

use crate::common::{config, csv_column, json_of, outcome, run_study, shared_reduced, tmp};
use tire::motion::{CentreMotion, CoSimulation};
use tire::{GroundKind, ReducedTire, RigConfig, RigResult, Symmetry, run_cleat};

/// The `[rig]` tables of a flat road without cleat, from the start (`settle_time = 0`) for
/// `record` seconds.
fn road(record: f64) -> String {
    format!(
        "[rig]\nsettle_time = 0.0\nrecord_time = {record}\n\
         [rig.ground]\nkind = \"road\"\ncleat = false\n"
    )
}

/// `cleat` on the small tire with the top-level keys and `tables` appended: (exit code,
/// stderr).
fn cleat(case: &str, tables: &str) -> (i32, String) {
    let (file, _) = shared_reduced();
    let dir = tmp(&format!("centre-motion-{case}"));
    let cfg = config(&dir, "cleat.toml", "", file, tables);
    let o = run_study("cleat", &["--quiet", "--json"], &cfg, &dir.join("out"));
    let (code, _, err) = outcome(&o);
    assert!(!err.contains("panicked"), "{case}: {err}");
    (code, err)
}

/// Bad series and rigs that do not fit a prescribed motion exit 2 with one line naming the
/// field (`rig.wheel.centre_motion.…`, or the rig's key that conflicts with it), before the
/// run.
#[test]
fn centre_motion_is_refused_with_the_field_named() {
    let motion = "[rig.wheel.centre_motion]\n";
    let cases: [(&str, String, &str); 8] = [
        (
            "time-not-increasing",
            format!("{}{motion}time = [0.0, 0.01, 0.01]\n", road(0.02)),
            "rig.wheel.centre_motion.time[2]",
        ),
        (
            "time-nan",
            format!("{}{motion}time = [0.0, nan]\n", road(0.02)),
            "rig.wheel.centre_motion.time[1]",
        ),
        (
            "lengths",
            format!("{}{motion}time = [0.0, 0.01]\nheight = [0.5]\n", road(0.02)),
            "rig.wheel.centre_motion.height",
        ),
        (
            "height-negative",
            format!(
                "{}{motion}time = [0.0, 0.01]\nheight = [0.5, -0.1]\n",
                road(0.02)
            ),
            "rig.wheel.centre_motion.height[1]",
        ),
        (
            "camber-beyond-rig",
            format!(
                "{}{motion}time = [0.0, 0.01]\ncamber = [0.0, 0.6]\n",
                road(0.02)
            ),
            "rig.wheel.centre_motion.camber[1]",
        ),
        (
            "step-not-positive",
            format!(
                "{}{motion}time = [0.0]\ncommunication_step = 0.0\n",
                road(0.02)
            ),
            "rig.wheel.centre_motion.communication_step",
        ),
        (
            "drum",
            format!("[rig.ground]\nkind = \"drum\"\n{motion}time = [0.0]\n"),
            "rig.ground.kind",
        ),
        (
            "camber-deg-too",
            format!(
                "{}[rig.wheel]\ncamber_deg = 1.0\n{motion}time = [0.0]\n",
                road(0.02)
            ),
            "rig.wheel.camber_deg",
        ),
    ];
    for (case, tables, field) in &cases {
        let (code, err) = cleat(case, tables);
        assert_eq!(code, 2, "{case}: exit {code}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{case}: one line: {err}");
        assert!(err.contains(field), "{case}: `{field}` not in: {err}");
    }
}

/// A prescribed height ramp (2 mm down over 20 ms) at a communication step of 1 ms (5 internal
/// steps of 0.2 ms): `forces.csv` has one row per communication step at `t = (k + 1) H`, and
/// the lowered wheel centre carries more load: F_z at the end above the start by more than
/// 500 N (the small tire's vertical stiffness is several MN/m: 0.5 mm lower carries about
/// 3 kN more in `constant_centre_motion_reproduces_the_fixed_wheel_centre`; 2 mm give well
/// over 500 N even at a tenth of that).
#[test]
fn centre_motion_runs_one_row_per_communication_step() {
    let (file, _) = shared_reduced();
    let red = ReducedTire::load(file).unwrap();
    let rig = {
        let mut r = RigConfig::default();
        r.ground.kind = GroundKind::Road;
        r.ground.cleat = false;
        r
    };
    let h0 = CoSimulation::rig_start(&red, &rig).unwrap().height;
    let dir = tmp("centre-motion-ramp");
    let tables = format!(
        "{}[rig.wheel.centre_motion]\ntime = [0.0, 0.02]\nheight = [{h0:?}, {:?}]\n\
         communication_step = 0.001\n",
        road(0.02),
        h0 - 0.002
    );
    let cfg = config(
        &dir,
        "cleat.toml",
        "vtk_interval = 0.0\nvtk_tire_interval = 0.0",
        file,
        &tables,
    );
    let out = dir.join("out");
    json_of(&run_study("cleat", &["--quiet", "--json"], &cfg, &out));
    let t = csv_column(&out.join("forces.csv"), "t_s");
    assert_eq!(t.len(), 20, "rows: {t:?}");
    for (k, t) in t.iter().enumerate() {
        assert!((t - (k + 1) as f64 * 1e-3).abs() < 1e-12, "t[{k}] = {t}");
    }
    let fz = csv_column(&out.join("forces.csv"), "fy_N");
    assert!(
        fz[19] > fz[0] + 500.0,
        "F_z {} -> {} with the centre lowered by 2 mm",
        fz[0],
        fz[19]
    );
}

/// Largest difference of the spindle loads of two runs over their samples \[N\] (moments
/// divided by the tire's radius), after checking their times agree.
fn largest_difference(a: &RigResult, b: &RigResult, radius: f64) -> f64 {
    assert_eq!(a.samples.len(), b.samples.len());
    let mut worst = 0.0f64;
    for (p, q) in a.samples.iter().zip(&b.samples) {
        assert!((p.t - q.t).abs() < 1e-12, "t {} vs {}", p.t, q.t);
        for d in [
            p.fx - q.fx,
            p.fy - q.fy,
            p.fz - q.fz,
            (p.mx - q.mx) / radius,
            (p.my - q.my) / radius,
            (p.mz - q.mz) / radius,
        ] {
            worst = worst.max(d.abs());
        }
    }
    worst
}

/// Second formulation: the rig with its wheel centre fixed at the rolling preload's height and
/// its spin prescribed at the start's rate (`run_cleat`'s own stepping, `rig_step`) against the
/// same rig driven by a prescribed motion that holds that height and spin rate
/// (`CoSimulation::do_step`: the ground set again every step, the frame acceleration zero).
/// Reference: both take the same internal steps of the same equations, so the loads agree to
/// round-off (the speed `v` enters the motion as `v/3.6·3.6`; allowed 1e-9 of the load).
/// The check can fail: the same motion 0.5 mm lower differs by more than 100 N.
#[test]
fn constant_centre_motion_reproduces_the_fixed_wheel_centre() {
    let (file, _) = shared_reduced();
    let red = ReducedTire::load(file).unwrap();
    let mut fixed = RigConfig::default();
    fixed.ground.kind = GroundKind::Road;
    fixed.ground.cleat = false;
    fixed.settle_time = 0.0;
    fixed.record_time = 0.02;
    // (the co-simulation steps the full model)
    fixed.rolling.symmetry = Symmetry::Off;
    let start = CoSimulation::rig_start(&red, &fixed).unwrap();
    let road = fixed.clone();
    let held = |height: f64| {
        let mut r = road.clone();
        r.wheel.centre_motion = Some(CentreMotion {
            time: vec![0.0, 0.01],
            height: Some(vec![height; 2]),
            velocity_x: None,
            velocity_y: None,
            velocity_z: None,
            yaw: None,
            camber: None,
            spin_rate: Some(vec![start.spin_rate; 2]),
            communication_step: None,
        });
        r
    };
    fixed.wheel.spin_rate = Some(start.spin_rate);
    let a = run_cleat(&red, &fixed, &mut |_| {}).unwrap();
    let b = run_cleat(&red, &held(start.height), &mut |_| {}).unwrap();
    let c = run_cleat(&red, &held(start.height - 5e-4), &mut |_| {}).unwrap();
    assert_eq!(a.samples.len(), 100);
    let load = fixed.load;
    let vertical = a.samples.last().unwrap().fy;
    assert!(
        (vertical - load).abs() < 0.05 * load,
        "F_z {vertical} carries the preload"
    );
    let r = red.outer_radius;
    let same = largest_difference(&a, &b, r);
    let lower = largest_difference(&a, &c, r);
    println!("fixed vs prescribed constant motion: {same:.3e} N; 0.5 mm lower: {lower:.1} N");
    assert!(same <= 1e-9 * load, "{same} N");
    assert!(lower > 100.0, "{lower} N");
}
