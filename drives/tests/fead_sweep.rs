//! The design study's rotational modes against the time simulation (issue 36): an engine-order
//! sweep on the flowing model (drives::fead::run_fead) through the crossing of the 2nd engine
//! order with the drive's first rotational mode, as predicted by the design study's Campbell
//! diagram (drives::fead_design).
//!
//! The rotational model holds the belt on the pulleys over the wraps (drives::fead_design::
//! modes: the spans are the only springs). The flowing model's tanh friction law
//! `μ p tanh(κ v_slip)` (Ribaric Table 6-1: κ = 40 s/m) couples belt and pulley by a creep
//! damper of `μ p κ` per length instead: the belt's stretch reaches `δ = √(EA/(ω μ p κ))` into
//! every wrap (a diffusion length), a compliance in series with the spans. On the two-pulley
//! drive below at 46 Hz, `p = T/r` = 8 kN/m, δ ≈ 37 mm at κ = 40 s/m and 5 mm at 2000 s/m.
//! Measured 2026-12-02 (order-2 peak of the driven pulley's speed, 50 rpm grid, predicted
//! 46.43 Hz at 1392.9 rpm): κ = 40 s/m peak near 1300 rpm (43.3 Hz, −7 %), κ = 400 s/m near
//! 1355 rpm (45.2 Hz, −2.7 %), κ = 2000 s/m 45.46 Hz (−2.1 %, the test below): the flowing
//! model approaches the rotational model as the wraps stiffen, which is what the test checks
//! at κ = 2000 s/m.
//!
//! The default six-pulley drive (tensioner dry friction and damping removed, β = 2e-4 s; not
//! asserted here): the alternator-dominated first mode, predicted at 49.4 Hz (order 2 at
//! 1482 rpm), peaks in the sweep near 1275–1290 rpm (42.5–43 Hz, −13 %) at κ = 40 and
//! 400 s/m alike; κ = 2000 s/m does not converge (Newton at the first step). Diagnosis
//! (issue 36 item 2, 2026-12-04, `cargo run --release -p drives --example fead_ringdown`: the
//! flowing model's free ring-down after a 4 ms torque pulse on the alternator, crank held at
//! 1482 rpm, peak of the alternator speed's spectrum on a 0.05 Hz grid):
//!
//! * the ring-down reproduces the sweep: 42.35 Hz at κ = 40 s/m, with the design model's mode
//!   shape (power steering 0.26, idler 0.04, arm −0.34 per alternator; design 0.25, 0.06,
//!   −0.33): the same mode, 27 % less stiff. Not the cause: belt speed (500 rpm: 42.25 Hz),
//!   belt mass (×0.1: 42.55), bending stiffness (×0.01: 41.9), free modes (40: 42.35), mesh
//!   (20/6 mm: 41.9), the arm's geometry (installed and operating angles agree to 1e-4 rad)
//!   and coupling (stiff spring ×1000: design 60.5 Hz, flowing 50.5 Hz, −16.5 %);
//! * the tanh law's creep compliance on the adhesion arcs (above): κ = 40, 100, 200, 400 s/m
//!   give 42.35, 43.10, 43.45, 43.75 Hz, linear in κ^−½ (a diffusion length), extrapolated
//!   to 44.4 Hz (−10 %) for κ → ∞;
//! * the slip arcs of the loaded pulleys (crank 32°, alternator 15°, a/c 8.5°, power
//!   steering 5°): there friction is saturated and holds no belt, a compliance the design
//!   model (belt held on the whole wrap) does not have. Every load torque × 0.01: κ = 40,
//!   100, 200, 400 s/m give 43.30, 44.45, 45.35, 45.90 Hz, extrapolated 47.3 Hz (−4.3 % of
//!   the unloaded design's 49.45 Hz); the loads lower the flowing mode by 2.2 % at κ = 40
//!   and 4.7 % at κ = 400 (about 6 % extrapolated), the design model with each slip arc's
//!   capstan compliance `r (1 − e^{−μ φ_s})/μ` added to the span leaving it by 4.2 % (47.3
//!   Hz). The two effects move in opposite senses with κ (the sharper law shortens the creep
//!   zones and sharpens the sliding arcs): hence "κ = 40 and 400 alike";
//! * left: about −4 % with no load and κ → ∞, of the order of the discretisation's effects
//!   (penalty × 100: +2 % at κ = 40, −0.7 % at 400; 4 mm wrap elements: +0.9 % at 400).
//!
//! So the −14 % (ring-down, κ = 40 s/m) is not one missing term but about a third each (in
//! log terms −4.7, −6.3 and −4.4 %): the regularised friction's creep (a flowing-model
//! artefact that vanishes as κ → ∞, slowly: κ^−½; the extrapolation assumes the trend
//! holds beyond the κ = 400 s/m that converges), the slip arcs' compliance (physics the
//! rotational model leaves out although the design study computes the arcs) and a residual
//! within the flowing model's discretisation. A rotational model with the slip arcs'
//! compliance would predict 47.3 Hz; the design study is not changed here.

use drives::fead::{EngineOrder, FeadConfig, run_fead};
use drives::fead_design::{DesignConfig, run_design};

// Reference: the design study's predicted crossing of order 2 with rotational mode 1
// (f = √(2 k r²/J)/(2π), k = EA/L, the closed form checked in drives::fead_design's unit
// tests). The sweep: 9 engine speeds from −8 % to +8 % of the predicted crossing in 2 % steps,
// crank speed amplitude 0.2 % of the mean (order 2 only), belt damping β = 2e-4 s (ζ ≈ 0.03 at
// 46 Hz: the peak of the damped response lies within 0.1 % of the undamped frequency),
// κ = 2000 s/m (module documentation). The peak of the driven pulley's speed amplitude (max −
// min over the settled window, over the crank's) located by a parabola through the largest
// and its neighbours must lie within 5 % of the prediction (measured −2.1 %) and inside the
// grid. 9 points of about 0.6 s simulated: 16 s in release (2026-12-02, shared 2-core machine).
#[test]
fn two_pulley_order_sweep_peaks_at_the_predicted_mode() {
    let mut cfg = FeadConfig {
        drive: belt::Layout::two_pulley(
            0.45,
            0.05,
            0.05,
            belt::Signal::constant(0.0),
            0.02,
            belt::Signal::schedule(vec![(0.0, 0.0), (0.1, 2.0)]),
            belt::Section::default(),
            400.0,
        ),
        ..FeadConfig::default()
    };
    cfg.drive.damping.beta = 2e-4;
    cfg.drive.contact.friction = contact::friction::FrictionSpec::Tanh {
        mu: 1.2,
        kappa: 2000.0,
    };
    cfg.run.settle = 0.3;
    let a = 0.002;
    cfg.engine.orders = vec![EngineOrder {
        order: 2.0,
        amplitude: a,
        phase: 0.0,
    }];
    let design = run_design(&DesignConfig {
        drive: cfg.drive.clone(),
        engine: cfg.engine.clone(),
        ..DesignConfig::default()
    })
    .unwrap();
    let crossing = design
        .campbell
        .crossings
        .iter()
        .find(|x| x.curve.starts_with("rotational mode 1") && x.order == 2.0)
        .expect("order 2 crosses the first rotational mode in the engine-speed range");
    let predicted = crossing.frequency_hz;
    let rpm: Vec<f64> = (-4..=4)
        .map(|k| crossing.engine_rpm * (1.0 + 0.02 * f64::from(k)))
        .collect();
    cfg.engine.speeds_rpm = rpm.clone();
    let sim = run_fead(&cfg, |_| {}).unwrap();
    let amp: Vec<f64> = sim
        .points
        .iter()
        .map(|p| {
            assert!(p.steady, "{} rpm not steady", p.engine_rpm);
            let w = p.engine_rpm * std::f64::consts::PI / 30.0;
            let e = &p.pulley_speed[1];
            0.5 * (e.max - e.min) / (a * w)
        })
        .collect();
    let k = (0..amp.len())
        .max_by(|&i, &j| amp[i].total_cmp(&amp[j]))
        .unwrap();
    assert!(
        k > 0 && k + 1 < amp.len(),
        "peak at the grid's end: {amp:?}"
    );
    // vertex of the parabola through the three points (equal steps)
    let (l, c, r) = (amp[k - 1], amp[k], amp[k + 1]);
    let step = rpm[k + 1] - rpm[k];
    let peak_rpm = rpm[k] + 0.5 * step * (l - r) / (l - 2.0 * c + r);
    let peak = 2.0 * peak_rpm / 60.0;
    eprintln!(
        "predicted {predicted:.2} Hz ({:.1} rpm); response {:?}; peak {peak:.2} Hz ({:+.2} %)",
        crossing.engine_rpm,
        rpm.iter()
            .zip(&amp)
            .map(|(r, a)| format!("{r:.0}: {a:.2}"))
            .collect::<Vec<_>>(),
        100.0 * (peak / predicted - 1.0)
    );
    assert!(
        (peak / predicted - 1.0).abs() < 0.05,
        "peak {peak} Hz against {predicted} Hz"
    );
}

// Reference: the flowing model's free ring-down (drives::ringdown: a 4 ms pulse of 0.5 N m on
// the driven pulley after 0.3 s ramps and 0.3 s of settling, 0.4 s recorded, the peak of the
// driven speed's spectrum on a 0.05 Hz grid) on a two-pulley drive with short spans (0.2 m,
// r = 0.05 m, J = 0.02 kg m², T0 = 400 N, crank at 145 rad/s: v = 7.25 m/s) under a load of
// 12 N m (slip arcs of 30°) and of 0.12 N m (0.3°), against the design study's rotational
// model with the creep theory's wrap compliance (drives::fead_design::modes; its closed form
// √((k_0 + k_1) r²/J)/(2π), k_i = EA/(L + ℓ_i), is checked in drives::fead_design's unit
// tests). κ = 2000 s/m: the creep theory's saturated slip arcs need κ v_slip ≫ 1, and the
// creep speed at the slip arcs' exits, v ΔT/EA ≈ 0.011 m/s, gives κ v_slip ≈ 23 (at
// κ = 400 s/m only 4.6: measured 63.95 Hz loaded, the slip arcs partly held).
//
// Measured 2026-12-05 (release, 2 s per ring-down): held wrap 69.65 Hz at both loads; creep
// model 65.31 Hz loaded, 69.60 Hz at 0.12 N m; flowing 62.15 and 67.20 Hz. Tolerances:
// (1) the load's effect f(12 N m)/f(0.12 N m), which cancels what the two loads share (the
// tanh law's creep on the adhesion arcs, ∝ κ^−½, and the discretisation: −3.4 % at
// 0.12 N m), is the creep model's within 2.5 % (measured: flowing −7.5 %, creep model −6.2 %,
// held wrap 0 %: the held model fails it); (2) the loaded frequency lies within 6 % below the
// creep model's (measured −4.8 %: the −3.4 % shared residual plus the 1.4 % of (1); the held
// model's 10.8 % fails it).
#[test]
fn two_pulley_ring_down_rings_at_the_creep_model_frequency() {
    use belt::{Layout, Section, Signal};
    use drives::fead_design::modes::{WrapModel, rotational_model_with};
    use drives::fead_design::steady_state;
    use drives::ringdown::{RingDownSettings, ring_down, spectrum_peaks};
    use flowing::belt::FlowingBelt;
    use mbd_core::integrators::AlphaConfig;
    let (dist, r, j, t0, crank, kappa) = (0.2, 0.05, 0.02, 400.0, 145.0, 2000.0);
    let ring = |q: f64| -> (f64, f64, f64) {
        let mut layout = Layout::two_pulley(
            dist,
            r,
            r,
            Signal::schedule(vec![(0.0, 0.0), (0.3, crank)]),
            j,
            Signal::schedule(vec![(0.0, 0.0), (0.3, q)]),
            Section::default(),
            t0,
        );
        layout.damping.beta = 2e-4;
        layout.contact.friction = contact::friction::FrictionSpec::Tanh { mu: 1.2, kappa };
        let drive = layout.resolve().unwrap();
        let s = steady_state(&drive, crank).unwrap();
        let first =
            |w: WrapModel| rotational_model_with(&drive, &s, w).modes().unwrap()[0].frequency_hz;
        let model = FlowingBelt::new(&drive, &FeadConfig::default().models.flowing).unwrap();
        let rd = ring_down(
            model,
            AlphaConfig {
                h: 2.5e-4,
                rho_inf: 0.8,
                subdivisions: drives::speed_loss::STEP_SUBDIVISIONS,
                ..Default::default()
            },
            &RingDownSettings {
                pulley: 1,
                ramp: 0.3,
                settle: 0.3,
                pulse_torque: 0.5,
                pulse_duration: 0.004,
                record: 0.4,
            },
        )
        .unwrap();
        let peaks = spectrum_peaks(&rd.times, &rd.pulley_speeds[1], [10.0, 200.0], 0.05, 0.05);
        let peak = peaks
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .expect("a peak")
            .0;
        let (creep, held) = (first(WrapModel::Creep), first(WrapModel::Held));
        eprintln!(
            "{q} N m: slip arcs {:.1}°, {:.1}°; held {held:.2} Hz, creep {creep:.2} Hz, \
             flowing {peak:.2} Hz (peaks {peaks:?})",
            s.wraps[0].slip_arc.to_degrees(),
            s.wraps[1].slip_arc.to_degrees()
        );
        (peak, creep, held)
    };
    let (flow, creep, held) = ring(12.0);
    let (flow0, creep0, held0) = ring(0.12);
    let effect = (flow / flow0) / (creep / creep0);
    eprintln!(
        "load effect: flowing {:+.2} %, creep {:+.2} %, held {:+.2} %",
        100.0 * (flow / flow0 - 1.0),
        100.0 * (creep / creep0 - 1.0),
        100.0 * (held / held0 - 1.0)
    );
    assert!((effect - 1.0).abs() < 0.025, "load effect off by {effect}");
    let gap = flow / creep - 1.0;
    assert!(gap < 0.0 && gap > -0.06, "{flow} Hz against {creep} Hz");
}
