//! The speed dips of the cleat test (issue 21 item 4; `flowing::tire::dips`): the cleat's
//! enveloping profile against the tire's geometry, and the predicted dip speeds against a
//! cleat sweep.

use flowing::tire::*;

mod common;
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
