//! The slider-crank case (moved from the unit tests of `cases/src/slider_crank.rs`, so that the
//! library is not compiled a second time for its unit tests).

use flowmbd_cases::slider_crank::SliderCrank;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};

// generalized-α follows the closed-form slider kinematics (analytical) to 1e-4 m over a
// quarter revolution
#[test]
fn slider_follows_the_closed_form() {
    let c = SliderCrank {
        crank_length: 0.1,
        rod_length: 0.3,
        masses: [1.0, 2.0, 3.0],
        omega: 2.0 * std::f64::consts::PI,
        theta0: 0.3,
    };
    let (sys, s0) = c.model().unwrap();
    assert!((s0.q[SliderCrank::SLIDER_X] - c.closed_form(0.3)).abs() < 1e-12);
    let mut worst = 0.0f64;
    GeneralizedAlpha::new(AlphaConfig {
        h: 1e-3,
        rho_inf: 0.8,
        ..Default::default()
    })
    .integrate(&sys, s0, 0.25, |s| {
        let x = c.closed_form(c.crank_angle(s.t));
        worst = worst.max((s.q[SliderCrank::SLIDER_X] - x).abs());
    })
    .unwrap();
    assert!(worst < 1e-4, "{worst}");
}
