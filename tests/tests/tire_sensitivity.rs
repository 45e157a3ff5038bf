//! Sensitivity studies of the cleat test (Ribaric §8.4) and the force balance of the steadily
//! rolling tire before the cleat, on the coarse generated truck tire (96 x 8 elements, 33 contact
//! nodes, 50 free-node modes).

use tire::*;

use crate::common;
use common::{coarse_reduced_tire as tire, rig};

/// Mean `(F_y, Σλ)` over the last 50 ms of steady rolling without a cleat.
fn steady(rc: &RigConfig) -> (f64, f64) {
    let r = run_cleat(tire(), rc, &mut |_| {}).unwrap();
    let b = r.before_cleat();
    let t_end = b.last().unwrap().t;
    let w: Vec<&Sample> = b.iter().filter(|s| s.t > t_end - 0.05).collect();
    let n = w.len() as f64;
    (
        w.iter().map(|s| s.fy).sum::<f64>() / n,
        w.iter().map(|s| s.normal_sum).sum::<f64>() / n,
    )
}

#[test]
fn more_damping_lowers_the_vertical_peak() {
    // Ribaric §8.4.1, Fig. 8-9: 3 % modal damping (modes 5 and 12) gives a lower vertical
    // spectral peak than 1 %.
    // The ratio p3/p1 is sensitive to differences in the free-node mode shapes at the level of
    // the eigen solver's tolerance (issue 37, 2026-12-06; the 50 frequencies equal to 1e-14 in
    // every case): 0.613 on main 2e8092f (block 24), 0.607 with block 8, 0.539 with the
    // per-pair test and basis 4·nev (p1 4214 N, p3 2272 N), 0.581 with the same solver and
    // only another pseudo-random Lanczos start block (p1 4049 N, p3 2351 N). The lightly
    // damped (1 %) peak moves most. The truncation at 50 modes splits no pair here (modes 49-51
    // at 253.10 / 253.67 / 258.36 Hz: the contact-node boundary breaks the axisymmetry).
    let red = tire();
    let mut lo = rig(GroundKind::Drum, true, 0.85);
    lo.damping.zeta1 = 0.01;
    lo.damping.zeta2 = 0.01;
    let hi = rig(GroundKind::Drum, true, 0.85);
    let peak = |rc: &RigConfig| {
        let r = run_cleat(red, rc, &mut |_| {}).unwrap();
        r.spectra().1.peak(10.0, 500.0).unwrap().1
    };
    let (p1, p3) = (peak(&lo), peak(&hi));
    assert!(p3 < 0.9 * p1, "Fy peak 3 % damping {p3} N vs 1 % {p1} N");
}

#[test]
fn steady_vertical_force_balance_before_the_cleat() {
    // Why the vertical spindle force of the steadily rolling tire differs from the preload
    // (issue 9): the preload solves the patch without friction for the Eulerian steady state, so
    // (a) without friction the normal contact forces carry the load (Σλ = load);
    // (b) the default spindle force (Newton's second law for the tire) equals Σλ in the steady
    // state, while the rim force of Ribaric (7.2) differs from it by the elastic residual of
    // the truncated basis under the centrifugal load, which grows as v² (second formulation);
    // (c) with friction the patch shear adds normal force at the locked spindle height.
    let mut a30 = rig(GroundKind::Road, false, 0.0);
    a30.speed_kmh = 30.0;
    a30.settle_time = 0.3;
    a30.record_time = 0.0;
    let mut a60 = a30.clone();
    a60.speed_kmh = 60.0;
    let rim = |rc: &RigConfig| {
        let mut r = rc.clone();
        r.rolling.spindle_force = SpindleForceMethod::Rim;
        r
    };
    let (fy30, sl30) = steady(&a30);
    let (fy60, sl60) = steady(&a60);
    let (rim30, _) = steady(&rim(&a30));
    let (rim60, _) = steady(&rim(&a60));
    let load = a30.load;
    for (fy, sl, v) in [(fy30, sl30, 30), (fy60, sl60, 60)] {
        assert!(
            (sl - load).abs() < 0.005 * load,
            "Σλ {sl} N vs load {load} N at {v} km/h without friction"
        );
        assert!(
            (fy - sl).abs() < 1e-6 * load,
            "Fy {fy} N vs Σλ {sl} N at {v} km/h"
        );
    }
    let (d30, d60) = (rim30 - sl30, rim60 - sl60);
    println!("rim force − Σλ: {d30} N at 30 km/h, {d60} N at 60 km/h");
    assert!(
        d60.abs() < 0.02 * load,
        "rim-force residual {d60} N at 60 km/h"
    );
    let ratio = d60 / d30;
    assert!(
        (2.5..6.0).contains(&ratio),
        "rim force − Σλ: {d30} N at 30, {d60} N at 60 km/h (ratio {ratio}, v² gives 4)"
    );
    let mut f60 = a60.clone();
    f60.rolling.friction = 0.85;
    let (fyf, slf) = steady(&f60);
    assert!(
        slf > sl60,
        "with friction Σλ {slf} N, without {sl60} N (Fy {fyf} vs {fy60} N)"
    );
}
