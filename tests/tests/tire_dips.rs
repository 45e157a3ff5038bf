//! The speed dips of the cleat test (issue 21 item 4; `tire::dips`): the cleat's
//! enveloping profile against the tire's geometry, and the predicted dip speeds against a
//! cleat sweep.

use fe_model::generate::TireConfig;
use tire::*;

use crate::common;
use common::coarse_reduced_tire as tire;

#[test]
fn the_cleat_is_felt_where_the_undeformed_tire_comes_within_its_height() {
    // Geometric reference: the undeformed tire (radius R_t) pressed by d onto a ground of
    // radius R_d is less than the cleat height h above it for |x| < √(2 R_e (h + d)),
    // 1/R_e = 1/R_t + 1/R_d (`geometric_envelope_half_length`). The coarse tire's 33 contact
    // nodes span ±0.17 m, beyond that stretch, so the profile's support is the geometric one
    // up to the node spacing (34 mm: the cleat is felt once it reaches a node row), and the
    // flat road envelopes a longer stretch than the convex drum (Ribaric §8.5).
    let red = tire();
    let mut lengths = Vec::new();
    for kind in [GroundKind::Drum, GroundKind::Road] {
        let g = GroundConfig {
            kind,
            ..GroundConfig::default()
        };
        let p = enveloping_profile(red, &g, 4448.2, 1e-3, 0.0).unwrap();
        let half = geometric_envelope_half_length(red.outer_radius, &g, p.deflection);
        assert!(
            p.node_span[1] > half + 0.02 && p.node_span[0] < -half - 0.02,
            "{kind:?}: nodes {:?} do not cover ±{half} m",
            p.node_span
        );
        for edge in [-p.support[0], p.support[1]] {
            assert!(
                edge < half + 0.005 && edge > half - 0.040,
                "{kind:?}: profile edge {edge} m vs geometric {half} m"
            );
        }
        // the preload is recovered away from the cleat (invariant)
        assert!(p.dfy[0].abs() < 1e-6 * 4448.2 && p.dfy[p.dfy.len() - 1].abs() < 1e-6 * 4448.2);
        lengths.push(p.length());
    }
    assert!(
        lengths[1] > lengths[0],
        "road {} vs drum {}",
        lengths[1],
        lengths[0]
    );
}

#[test]
#[ignore = "heavy: reduces the default tire with 187 contact nodes (~1 min idle) and runs 14 cleat tests (~30 s CPU)"]
fn predicted_dips_match_the_cleat_sweep_on_drum_and_road() {
    // Second formulation: the dip speeds of the enveloping filter (a half sine over the
    // model's enveloping length, filtering the loaded vertical mode) against the cleat sweep
    // of the rolling tire (the line amplitude of the vertical spindle force, 5 km/h steps).
    // 187 contact nodes (17 rows) so that the nodes cover the stretch over which the cleat is
    // felt (95 nodes span ±68 mm, shorter than the geometric ±105/125 mm). Measured
    // 2026-11-26: predicted drum 33.0, road 43.5 km/h; sweep drum 30, road 40 km/h.
    let fe = generated_tire(&TireConfig {
        patch_half_angle_deg: 16.0,
        ..TireConfig::default()
    })
    .unwrap();
    let red = reduce(
        &fe,
        &ReductionConfig {
            contact_nodes: 187,
            ..Default::default()
        },
    )
    .unwrap()
    .0;
    let cfg = DipConfig {
        sweep_speeds_kmh: (0..=6).map(|k| 25.0 + 5.0 * k as f64).collect(),
        ..DipConfig::default()
    };
    let mut first = Vec::new();
    for kind in [GroundKind::Drum, GroundKind::Road] {
        let mut rig = RigConfig::default();
        rig.ground.kind = kind;
        let d = ground_dips(&red, &rig, &cfg, &mut |_| {}).unwrap();
        let pred = *d
            .prediction
            .dips_kmh
            .iter()
            .rfind(|v| (25.0..=55.0).contains(*v))
            .expect("a predicted dip in 25-55 km/h");
        // the deepest local minimum of the sweep
        let a = &d.line_amplitude_n;
        let k = (1..a.len() - 1)
            .filter(|&i| a[i] < a[i - 1] && a[i] < a[i + 1])
            .min_by(|&i, &j| a[i].total_cmp(&a[j]))
            .expect("a dip in the sweep");
        let meas = d.sweep_speeds_kmh[k];
        assert!(
            (pred - meas).abs() <= 5.0,
            "{kind:?}: predicted {pred} km/h, sweep {meas} km/h ({a:?})"
        );
        first.push((pred, meas));
    }
    // Ribaric §8.5: the road's dip lies at a higher speed than the drum's
    assert!(
        first[1].0 > first[0].0 && first[1].1 > first[0].1,
        "{first:?}"
    );
}
