//! The half model of mirror-symmetric motion (`tire::mirror`) against the full model
//! (second formulation: `symmetry = "off"`) on the coarse generated tire rolling on the drum
//! with friction: the same spindle forces, spin rate and normal forces step by step, through
//! the cleat impact; and the fallback to the full model for an unsymmetric tire or start.

use tire::*;

use crate::common;
use common::{coarse_reduced_tire as tire, rig};

/// `steps` steps from the rig's rolling start on the drum with the cleat reaching the patch
/// centre after `cleat_time` \[s\], the contact solved to `contact_tolerance`: per step
/// `[Fx, Fy, Fz, θ̇, Σλ]`, and the model description.
fn run(
    red: &ReducedTire, symmetry: Symmetry, contact_tolerance: f64, cleat_time: f64, steps: usize,
) -> (Vec<[f64; 5]>, String) {
    let mut rc = rig(GroundKind::Drum, true, 0.85);
    rc.rolling.symmetry = symmetry;
    rc.rolling.contact_tolerance = contact_tolerance;
    rc.settle_time = cleat_time;
    let mut start = start_rolling(red, &rc).unwrap();
    let sim = &mut start.sim;
    let mut out = Vec::with_capacity(steps);
    for _ in 0..steps {
        sim.step().unwrap();
        let f = sim.spindle_force();
        out.push([
            f.fx,
            f.fy,
            f.fz,
            sim.state.theta_d,
            sim.total_normal_force(),
        ]);
    }
    (out, sim.symmetry().describe())
}

/// Largest difference per quantity between two histories, over the steps `from..to`.
fn worst(a: &[[f64; 5]], b: &[[f64; 5]], from: usize, to: usize) -> [f64; 5] {
    let mut w = [0.0f64; 5];
    for (x, y) in a[from..to].iter().zip(&b[from..to]) {
        for c in 0..5 {
            w[c] = w[c].max((x[c] - y[c]).abs());
        }
    }
    w
}

#[test]
fn half_model_steps_as_the_full_model_through_the_cleat() {
    let red = tire();
    // 300 steps of 0.2 ms, the cleat at the patch centre after 30 ms (its first contact about
    // step 160)
    let (half, dh) = run(red, Symmetry::Auto, 1e-12, 0.03, 300);
    let (full, df) = run(red, Symmetry::Off, 1e-12, 0.03, 300);
    let (full10, _) = run(red, Symmetry::Off, 1e-10, 0.03, 300);
    // the coarse tire: 149 coordinates, 33 contact nodes (11 on the mid-plane)
    assert!(
        dh.starts_with("mirror half model: 78 of 149 coordinates, 22 contact unknowns"),
        "{dh}"
    );
    assert_eq!(df, "full model (symmetry = \"off\")");
    let load = rig(GroundKind::Drum, true, 0.85).load;
    let range = full.iter().fold(0.0f64, |a, f| a.max((f[1] - load).abs()));
    assert!(range > 0.1 * load, "no cleat impact: {range} N");
    // rolling up to the cleat: the same forces to 1e-9 of the load, the same spin rate
    let before = worst(&half, &full, 0, 150);
    assert!(
        before[0] < 1e-9 * load && before[1] < 1e-9 * load && before[4] < 1e-9 * load,
        "{before:?}"
    );
    assert!(before[3] < 1e-12, "{before:?}");
    // through the impact the contact problem amplifies round-off (the cleat phase scatter):
    // the half model stays within three times the full model's own change when its contact
    // tolerance goes from 1e-10 to 1e-12
    let own = worst(&full10, &full, 0, 300);
    let after = worst(&half, &full, 0, 300);
    for c in [0, 1, 4] {
        assert!(
            after[c] <= 3.0 * own[c] + 1e-9 * load,
            "quantity {c}: half − full {} N, full's own {} N",
            after[c],
            own[c]
        );
    }
    // no lateral spindle force in either
    assert!(
        half.iter().chain(&full).all(|f| f[2].abs() < 1e-6 * load),
        "lateral spindle force"
    );
}

#[test]
fn unsymmetric_tire_or_start_steps_the_full_model() {
    // the coarse tire with one stiffness coupling that has no mirror image (contact node 1's
    // x and node 3's z, symmetric in K): not mirror-symmetric
    let mut red = tire().clone();
    let nf = red.n_free_modes;
    let (i, j) = (nf + 3, nf + 3 * 3 + 2);
    let e = 1e-3 * red.k[(i, i)];
    red.k[(i, j)] += e;
    red.k[(j, i)] += e;
    let modal = red.modal().unwrap();
    let err = mirror_half(&modal.tire).unwrap_err();
    assert!(err.contains("symmetric"), "{err}");
    let (_, d) = run(&red, Symmetry::Auto, 1e-10, 0.03, 1);
    assert!(d.starts_with("full model ("), "{d}");
    // the symmetric tire started from an unsymmetric state: the full model
    let red = tire();
    let modal = red.modal().unwrap();
    let half = mirror_half(&modal.tire).unwrap();
    let anti = (0..red.n_z()).find(|j| !half.kept.contains(j)).unwrap();
    let mut y0 = vec![0.0; red.n_z()];
    y0[half.kept[0]] = 1e-3;
    y0[anti] = 1e-6;
    let z0: Vec<f64> = (0..red.n_z())
        .map(|i| (0..red.n_z()).map(|j| modal.phi[(i, j)] * y0[j]).sum())
        .collect();
    let rc = rig(GroundKind::Drum, false, 0.85);
    let ground = Ground::new(rc.ground.clone(), -red.outer_radius, 10.0, 0.0, 1.0).unwrap();
    let sim = RollingTire::new(red, rc.rolling.clone(), ground, 0.0, 0.0, z0, 20.0).unwrap();
    let d = sim.symmetry().describe();
    assert!(d.contains("initial state is not mirror-symmetric"), "{d}");
}

#[test]
fn mirror_half_of_the_coarse_tire_is_consistent() {
    // invariants of the split: every coordinate is kept or dropped, the images pair up, the
    // weights count every node once
    let red = tire();
    let modal = red.modal().unwrap();
    let half = mirror_half(&modal.tire).unwrap();
    let nc = red.n_contact();
    assert!(half.kept.windows(2).all(|w| w[0] < w[1]));
    assert!(half.kept.len() < red.n_z() && half.kept.len() > red.n_z() / 3);
    for i in 0..nc {
        let p = half.partner[i];
        assert_eq!(half.partner[p], i);
        let (a, b) = (red.contact_positions[i], red.contact_positions[p]);
        assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] + b[1]).abs() < 1e-9);
    }
    let total: f64 = (0..nc).map(|i| half.weight(i)).sum();
    assert_eq!(total, nc as f64);
    let t = half_tire(&modal.tire, &half);
    assert_eq!(t.n_z(), half.kept.len());
    assert_eq!(t.tc.nrows(), 3 * nc);
}
