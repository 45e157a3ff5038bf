//! The FEAD sweep's step on a mesh that travels with the belt (`run.max_travel`, issue 37
//! item 4): the ANCF and nodal belts carry their elements through the wraps at the belt speed,
//! so each point's step is the model's step divided until the belt moves at most
//! `max_travel` elements per step; the flowing belt's stationary mesh keeps its step.

use belt::BeltModel;
use drives::fead::{FeadConfig, FeadModel, run_fead, travel_limited_step};

// Reference: the definition, in closed form: k = ⌈h v/(f ℓ)⌉ equal parts, the fewest with
// v h/k ≤ f ℓ.
#[test]
fn travel_limited_step_takes_the_fewest_whole_parts() {
    let (h, f, l) = (2.5e-4, 0.25, 0.0138);
    for v in [0.0, 1.0, 6.3, 11.8, 13.8, 13.81, 19.6, 27.5, 100.0] {
        let hp = travel_limited_step(h, f, Some(l), v);
        let k = h / hp;
        assert!((k - k.round()).abs() < 1e-9, "v = {v}: {k} parts");
        assert!(
            v * hp <= f * l * (1.0 + 1e-12),
            "v = {v}: travel {}",
            v * hp
        );
        if k > 1.5 {
            // one part fewer would travel too far
            assert!(
                v * h / (k - 1.0) > f * l,
                "v = {v}: {k} parts are not the fewest"
            );
        }
    }
    // 27.5 m/s on 13.8 mm elements at 0.25 ms: half an element a step, so two parts
    assert_eq!(travel_limited_step(h, f, Some(l), 27.5), h / 2.0);
    // a stationary mesh, no limit, or a belt at rest keep the step
    assert_eq!(travel_limited_step(h, f, None, 27.5), h);
    assert_eq!(travel_limited_step(h, 0.0, Some(l), 27.5), h);
    assert_eq!(travel_limited_step(h, f, Some(l), 0.0), h);
}

// Reference: the models' meshes (ANCF: `models.ancf.elements` equal elements on the belt;
// nodal: a uniform loop of the mounted path; flowing: a stationary mesh, no element travels).
#[test]
fn lagrangian_meshes_state_the_element_the_material_carries() {
    let cfg = FeadConfig::default();
    let drive = cfg.drive.resolve().unwrap();
    let ancf = drives::ancf_model::AncfBelt::new(&drive, &cfg.models.ancf).unwrap();
    let l = ancf.material_element().unwrap();
    let expected = drive.belt_length() / cfg.models.ancf.elements as f64;
    assert!((l - expected).abs() < 1e-12 * expected, "{l} vs {expected}");
    let nodal = flowing::belt::NodalBelt::new(&drive, &cfg.models.nodal.mesh).unwrap();
    let ln = nodal.material_element().unwrap();
    let n = nodal.fe.n_nodes() as f64;
    assert!((ln * n - drive.path().length()).abs() < 1e-12);
    // the nodal loop's elements are no longer than the mesh asked for
    let asked = cfg
        .models
        .nodal
        .mesh
        .span_element
        .min(cfg.models.nodal.mesh.arc_element);
    assert!(ln <= asked * (1.0 + 1e-9), "{ln} > {asked}");
    let flow = flowing::belt::FlowingBelt::new(&drive, &cfg.models.flowing).unwrap();
    assert_eq!(flow.material_element(), None);
}

// Reference: the default sweep's points in closed form (the crank's belt speed with the 2.5 %
// fluctuation, at the fastest speed of each point's ramp, against the ANCF belt's 12.7 mm
// elements at 0.25 ms): with run.ancf_max_travel = 0.5 the 800–2500 rpm points keep the
// model's step (at most 0.40 of an element a step) and 3500 rpm takes two parts (0.56).
#[test]
fn the_default_ancf_sweep_halves_only_the_fastest_point() {
    let cfg = FeadConfig::default();
    let drive = cfg.drive.resolve().unwrap();
    let l = drive.belt_length() / cfg.models.ancf.elements as f64;
    let h = cfg.models.ancf.step;
    let r = drive.pulleys()[0].radius;
    for (rpm, parts) in [(800.0, 1.0), (1500.0, 1.0), (2500.0, 1.0), (3500.0, 2.0)] {
        let v = rpm * std::f64::consts::PI / 30.0 * r * 1.025;
        let travel = v * h / l;
        assert_eq!(
            travel_limited_step(h, cfg.run.ancf_max_travel, Some(l), v),
            h / parts,
            "{rpm} rpm: {travel} elements a step"
        );
    }
}

// Reference: travel_limited_step at the point's crank speed (3500 rpm on the 75 mm crank with
// the 2.5 % fluctuation: 28.2 m/s, 7.0 mm per 0.25 ms against 0.2 of the ANCF belt's 12.7 mm
// elements: three parts); run.max_travel, which the ANCF belt does not take, at 1 (one part);
// the flowing belt keeps run.step.
#[test]
fn each_point_reports_its_travel_limited_step() {
    let mut cfg = FeadConfig::default();
    cfg.engine.speeds_rpm = vec![3500.0];
    cfg.run.ramp = 0.02;
    cfg.run.settle = 0.0;
    cfg.run.window = 0.005;
    cfg.run.max_settle = 0.0;
    cfg.run.max_travel = 1.0;
    cfg.run.ancf_max_travel = 0.2;
    let flow = run_fead(&cfg, |_| {}).unwrap();
    assert_eq!(flow.points[0].step_s, cfg.run.step);
    cfg.model = FeadModel::Ancf;
    let drive = cfg.drive.resolve().unwrap();
    let l = drive.belt_length() / cfg.models.ancf.elements as f64;
    let v = 3500.0 * std::f64::consts::PI / 30.0 * drive.pulleys()[0].radius * 1.025;
    let expected = travel_limited_step(cfg.models.ancf.step, cfg.run.ancf_max_travel, Some(l), v);
    assert_eq!(expected, cfg.models.ancf.step / 3.0);
    let a = run_fead(&cfg, |_| {}).unwrap();
    assert_eq!(a.points[0].step_s, expected);
    // the steps taken: the ramp and the window at that step
    let steps = ((cfg.run.ramp + a.points[0].window_s) / expected).round() as usize;
    assert!(a.steps.abs_diff(steps) <= 1, "{} steps vs {steps}", a.steps);
}
