//! The rotating-mesh nodal belt drive (Ribaric (5.1)–(5.8)) against the flowing-material form
//! (5.14) on the same mesh: the issue-8 validation "the flowing and the rotating-mesh nodal forms
//! agree within 2 % at the same mesh", and the element-passing line that only the rotating mesh
//! puts into the driven pulley's speed.

use belt::{BeltModel, Signal};
use drives::speed_loss::STEP_SUBDIVISIONS;
use drives::{SpeedLossConfig, SpeedLossPoint, speed_loss_sweep};
use flowing::belt::{BeltMesh, FlowingBelt, FlowingSettings, NodalBelt};
use flowing::spectrum::amplitude_spectrum;
use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha, Stepper};

/// Both models of Ribaric Table 6-1 on a uniform loop: `span` elements per span, `arc` per arc
/// (0.45 m spans, 0.157 m arcs; 20/7 and 80/28 give equal element lengths to 0.3 %).
fn uniform(span: usize, arc: usize) -> (NodalBelt, FlowingBelt) {
    let drive = drives::table_6_1::drive();
    let mesh = BeltMesh {
        span_element: 0.45 / span as f64,
        arc_element: std::f64::consts::PI * 0.05 / arc as f64,
        contact_margin_nodes: 1,
    };
    let settings = FlowingSettings {
        mesh,
        ..Default::default()
    };
    (
        NodalBelt::new(&drive, &mesh).unwrap(),
        FlowingBelt::new(&drive, &settings).unwrap(),
    )
}

fn sweep<M: BeltModel>(model: &mut M, torques: &[f64]) -> Vec<SpeedLossPoint> {
    // windows of 0.1 s: the rotating mesh's ripple averages out over several element passings
    let settings = SpeedLossConfig {
        torques: torques.to_vec(),
        window: 0.1,
        tolerance: 1e-3,
        max_hold: 3.0,
        ..Default::default()
    };
    speed_loss_sweep(model, &settings, |_, _| {})
        .unwrap_or_else(|f| panic!("sweep failed: {} (points {:?})", f.error, f.points))
        .0
}

/// Driven-pulley speed sampled every step from `t_from` to `t_to` \[s\], unloaded, driver spun up
/// to 62.8 rad/s over 0.3 s.
fn driven_speed_history<M: BeltModel>(model: &mut M, t_from: f64, t_to: f64, h: f64) -> Vec<f64> {
    model
        .set_signal(0, Signal::schedule(vec![(0.0, 0.0), (0.3, 62.8)]))
        .unwrap();
    model.set_signal(1, Signal::constant(0.0)).unwrap();
    let s0 = model.initial_state().unwrap();
    let alpha = GeneralizedAlpha::new(AlphaConfig {
        h,
        rho_inf: 0.6,
        subdivisions: STEP_SUBDIVISIONS,
        ..Default::default()
    });
    let mut st = alpha.stepper(&*model, s0).unwrap();
    let mut out = Vec::new();
    while st.state().t < t_to - 0.5 * h {
        st.step(&*model, Some(h)).unwrap();
        if st.state().t >= t_from - 0.5 * h {
            let s = st.state();
            out.push(model.pulley_speed(1, s.t, &s.v));
        }
    }
    out
}

/// Largest spectral amplitude within `±band` Hz of `f` \[Hz\].
fn line(spec: &flowing::spectrum::Spectrum, f: f64, band: f64) -> f64 {
    spec.frequencies
        .iter()
        .zip(&spec.amplitudes)
        .filter(|(x, _)| (*x - f).abs() <= band)
        .fold(0.0f64, |a, (_, y)| a.max(*y))
}

// Issue 8 / seed-000 note §1.5.2 ("no artificial polygonal excitation because the mesh does not
// rotate"): on the same uniform 54-element loop, the rotating mesh puts a line at the
// element-passing frequency v/h_e (≈ 140 Hz at 62.8 rad/s) into the driven pulley's speed; the
// flowing form's line there is orders of magnitude smaller. The nodal model is the second
// formulation that makes the flowing form's claimed advantage a measurable difference.
#[test]
fn only_the_rotating_mesh_has_the_element_passing_line() {
    let (mut nodal, mut flow) = uniform(20, 7);
    let h_e = nodal.fe.path().length() / nodal.fe.n_nodes() as f64;
    let f_e = 62.8 * 0.05 / h_e;
    let h = 2.5e-4;
    let (t0, t1) = (0.5, 0.9);
    let w_nodal = driven_speed_history(&mut nodal, t0, t1, h);
    let w_flow = driven_speed_history(&mut flow, t0, t1, h);
    let sn = amplitude_spectrum(&w_nodal, h, 4).unwrap();
    let sf = amplitude_spectrum(&w_flow, h, 4).unwrap();
    let (an, af) = (line(&sn, f_e, 5.0), line(&sf, f_e, 5.0));
    // the nodal line stands out of its neighbourhood (40–100 Hz and 180–400 Hz, no harmonics)
    let floor = sn
        .frequencies
        .iter()
        .zip(&sn.amplitudes)
        .filter(|(f, _)| (40.0..100.0).contains(*f) || (180.0..260.0).contains(*f))
        .fold(0.0f64, |a, (_, y)| a.max(*y));
    println!("f_e = {f_e:.1} Hz: nodal {an:.3e}, flowing {af:.3e} rad/s, nodal floor {floor:.3e}");
    assert!(an > 1e-3, "nodal element-passing line {an:e} rad/s");
    assert!(
        an > 3.0 * floor,
        "nodal line {an:e} vs neighbourhood {floor:e}"
    );
    assert!(af < 1e-3 * an, "flowing {af:e} vs nodal {an:e} rad/s");
}

// Issue 8: unloaded, the nodal form's driven pulley follows the driver (on the same uniform
// 54-element loop the element-passing ripple leaves a mean loss below 1e-4 relative), and under
// load its Δω lies above the flowing form's on this coarse loop (the polygonal ripple of the
// rotating mesh makes the tanh friction slip more); the ≤ 2 % agreement needs the finer loop of
// the ignored test below.
#[test]
fn nodal_speed_loss_on_a_coarse_uniform_loop() {
    let (mut nodal, mut flow) = uniform(20, 7);
    let pn = sweep(&mut nodal, &[0.0, 8.0]);
    let pf = sweep(&mut flow, &[0.0, 8.0]);
    println!("nodal {pn:?}\nflowing {pf:?}");
    assert!(
        pn[0].delta_omega.abs() / 62.8 < 1e-4,
        "{}",
        pn[0].delta_omega
    );
    let (dn, df) = (pn[1].delta_omega, pf[1].delta_omega);
    assert!(dn > df && dn < 1.25 * df, "nodal {dn} vs flowing {df}");
}

// Issue 8 validation: flowing and rotating-mesh nodal forms agree on Δω within 2 % at the same
// mesh (uniform, 216 elements of 5.6 mm, 28 per arc). On coarser loops the rotating mesh's
// polygonal excitation biases it upward (slip reference ω R at the pulley surface): +17 % at
// 54 elements, +2.1 % at 162. Heavy: the nodal model integrates 650 coordinates for ≈ 1.4 s.
#[test]
#[ignore = "heavy: the 216-element nodal model for 1.4 s of simulated time (several minutes)"]
fn flowing_and_nodal_agree_within_two_percent() {
    let (mut nodal, mut flow) = uniform(80, 28);
    let pn = sweep(&mut nodal, &[0.0, 8.0]);
    let pf = sweep(&mut flow, &[0.0, 8.0]);
    let (dn, df) = (pn[1].delta_omega, pf[1].delta_omega);
    println!("Δω(8 N m): nodal {dn}, flowing {df}");
    assert!((dn / df - 1.0).abs() < 0.02, "nodal {dn} vs flowing {df}");
}
