//! The design study's rotational modes against the time simulation (issue 36 item 2): the
//! flowing model (drives::fead::run_fead, drives::ringdown) against the rotational model of the
//! design study (drives::fead_design::modes) and its Campbell diagram.
//!
//! The rotational model holds the belt on each wrap's adhesion arc and lets it stretch on the
//! slip arc, where friction is saturated (creep theory; `design.wrap = "creep"`, the default:
//! each span in series with the slip arc it leaves, `EA c_w = r |ΔT|/(μ (T_out − T_c))` for
//! the linear law); `wrap = "held"` holds it on the whole wrap (the spans the only springs, the
//! model before 2026-12-04). The flowing model's tanh law `μ p tanh(κ v_slip)` (Ribaric Table
//! 6-1: κ = 40 s/m) differs from creep theory in two ways, both vanishing as κ → ∞: on the
//! adhesion arcs it couples belt and pulley by a creep damper of `μ p κ` per length, so the
//! belt's stretch reaches `δ = √(EA/(ω μ p κ))` into every wrap (a diffusion length: a
//! compliance ∝ κ^−½ the creep theory does not have); on the slip arcs it saturates only where
//! `κ v_slip ≫ 1`, `v_slip` up to the creep speed `v ΔT/EA` (at smaller κ the slip arcs are
//! partly held). On the two-pulley drive of the order sweep below (0.45 m spans at 46 Hz,
//! `p = T/r` = 8 kN/m) δ ≈ 37 mm at κ = 40 s/m and 5 mm at 2000 s/m; measured 2026-12-02
//! against the held model's 46.43 Hz (its small load moves the creep model only to 46.21 Hz):
//! κ = 40 s/m 43.3 Hz, κ = 400 s/m 45.2 Hz, κ = 2000 s/m 45.46 Hz; the test below at
//! κ = 2000 s/m, 2026-12-04: 45.45 Hz, −1.66 % of the creep model's 46.21 Hz.
//!
//! The default six-pulley drive (tensioner dry friction and damping removed, β = 2e-4 s; not
//! asserted here), 2026-12-04, `cargo run --release -p drives --example fead_ringdown --
//! kappa=K [load=F]` (the flowing model's free ring-down after a 4 ms pulse on the alternator,
//! crank held at 1482 rpm, the peak of the alternator speed's spectrum on a 0.05 Hz grid; 7 s
//! per run):
//!
//! * design, first mode (alternator 1, power steering 0.27, idler 0.07, arm −0.32): **45.82 Hz**
//!   with the creep wrap, 49.40 Hz held. Slip arcs: crank 31.8°, alternator 14.9°, a/c 8.5°,
//!   power steering 5.3°, water pump 3.1°; as lengths of belt `EA c_w`: crank 58.8 mm (the
//!   earlier estimate `r (1 − e^{−μ φ_s})/μ` gave 30.4 mm: it is the driven pulleys' formula,
//!   short by `e^{μ φ_s}` on the driver), 6.2, 8.1, 5.7 and 2.9 mm (within 1 % of the estimate;
//!   the St Venant–Kirchhoff law's tangent stiffness). The belt's mass (spans lumped
//!   consistently to their ends, wraps to their pulleys) would lower it by 0.3 % (45.67 Hz):
//!   left out;
//! * flowing ring-down: κ = 40, 100, 200, 400 s/m give 42.35, 43.10, 43.45, 43.75 Hz (the mode
//!   shape of the design's: power steering 0.26, idler 0.04, arm −0.34 at κ = 40), linear in
//!   κ^−½ (residuals below 0.03 Hz), extrapolated 44.38 Hz for κ → ∞; against the creep model
//!   −7.6 %, −4.5 % and −3.1 % (κ = 40, 400, ∞), against the held one −14.3 %, −11.4 %,
//!   −10.2 %. κ = 2000 s/m does not converge on this drive (Newton at the first steps);
//! * the loads: every load torque × 0.01 gives 43.30 Hz (κ = 40), 45.90 Hz (κ = 400),
//!   extrapolated 47.3 Hz, against 49.43 Hz (creep) and 49.45 Hz (held): the loads lower the
//!   flowing mode by 6.2 % (extrapolated), the creep model by 7.3 %, the held model by 0.1 %;
//! * left: −3.1 % loaded and −4.3 % unloaded at κ → ∞, of the order of the flowing model's
//!   discretisation (penalty × 100: +2 % at κ = 40, −0.7 % at 400; 4 mm wrap elements: +0.9 %
//!   at 400) and the belt's mass (−0.3 %). Not the cause (measured 2026-12-04 against the held
//!   model): belt speed (500 rpm: 42.25 Hz at κ = 40), belt mass (×0.1: 42.55), bending
//!   stiffness (×0.01: 41.9), free modes (40: 42.35), mesh (20/6 mm: 41.9), the arm's geometry
//!   (installed and operating angles agree to 1e-4 rad) and coupling (stiff spring ×1000).
//!
//! So the flowing model's −14.3 % against the held model at κ = 40 s/m is, in log terms, −7.5 %
//! of the slip arcs' compliance (physics, now in the design study), −4.7 % of the regularised
//! friction's creep on the adhesion arcs (a flowing-model artefact, ∝ κ^−½: 42.35 against
//! 44.38 Hz) and a residual of −3.2 %.

use drives::fead::{EngineOrder, FeadConfig, run_fead};
use drives::fead_design::{DesignConfig, run_design};

// Reference: the design study's predicted crossing of order 2 with rotational mode 1
// (f = √((k_0 + k_1) r²/J)/(2π), k_i = EA/(L + ℓ_i) with the slip arcs' lengths ℓ_i, the
// closed form checked in drives::fead_design's unit tests; the 2 N m load gives slip arcs of
// 4.8° and 46.21 Hz against the held wrap's 46.43 Hz). The sweep: 9 engine speeds from −8 %
// to +8 % of the predicted crossing in 2 % steps, crank speed amplitude 0.2 % of the mean
// (order 2 only), belt damping β = 2e-4 s (ζ ≈ 0.03 at
// 46 Hz: the peak of the damped response lies within 0.1 % of the undamped frequency),
// κ = 2000 s/m (module documentation). The peak of the driven pulley's speed amplitude (max −
// min over the settled window, over the crank's) located by a parabola through the largest
// and its neighbours must lie within 5 % of the prediction and inside the grid (measured
// 2026-12-02 −2.1 % against the held model; 2026-12-04 −1.66 % against the creep model).
// 9 points of about 0.6 s simulated: 16 s in release (2026-12-02, shared 2-core machine).
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
// Measured 2026-12-04 (release, 2 s per ring-down): held wrap 69.65 Hz at both loads; creep
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
