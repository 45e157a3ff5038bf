//! Issue 34 item 2: balances as invariants. Every belt report carries, per pulley, the residual
//! between the torque the pulley transmits and `Σ (T_in − T_out) r` from the reported spans, and
//! the power balance `power in = sliding losses (+ belt damping)`; at a steady state both vanish
//! (angular-momentum and energy balance of the belt). Checked on Ribaric's Table 6-1 drive
//! (speed-loss procedure), on the Pechstein–Gerstmayr drive (Exudyn's `beltDriveReevingSystem`,
//! shipped as `apps/belt/examples/pechstein-gerstmayr.toml`) and on the default `fead` drive,
//! for the flowing, nodal and ANCF models where they hold (the gaps are named at each test).

use belt::Report;
use drives::fead::{FeadConfig, FeadModel, run_fead};
use drives::table_6_1;
use drives::{SpeedLossConfig, speed_loss_sweep};
use flowing::belt::{
    AxialForce, BeltEquations, BeltMesh, BendingForce, ContactVelocity, FlowingBelt,
    FlowingSettings, NodalBelt, ViscousForce,
};

/// Largest relative residual allowed (issue 34 item 2: 0.5 %).
const TOL: f64 = 5e-3;

fn assert_balanced(what: &str, r: &Report) {
    let b = &r.balances;
    for p in &r.pulleys {
        println!(
            "{what}: {} torque {:.4} N m, spans {:.4} N m, residual {:.2e} N m",
            p.name, p.torque_n_m, p.span_torque_n_m, p.torque_residual_n_m
        );
    }
    println!(
        "{what}: torque residual {:.2e}, power in {:.3} W, sliding {:.3} W, residual {:.2e} \
         of {:.2} W",
        b.torque_residual_rel, b.power_in_w, b.sliding_w, b.power_residual_rel, b.driver_power_w
    );
    assert!(b.torque_residual_rel.abs() <= TOL, "{what}: torque {b:?}");
    assert!(b.power_residual_rel.abs() <= TOL, "{what}: power {b:?}");
}

// Table 6-1 (Ribaric): the speed-loss procedure's steady point at 10 N m, flowing model with
// the study's defaults (the linear model of Ribaric (5.5), `AxialForce::Linear`). With the
// spans' moments taken about the belt-line radius R the torque residual was 0.75 % (the
// deformed tight span acts 0.10–0.16 mm outside R); about the spans' lines of action it is
// 0.24 %, the power residual 0.33 %. At 30 N m this linear model misses by 0.74 % (torque) and
// 0.92 % (power): the contact forces on the whole belt carry a net moment of 0.21 N m in the
// steady state (0.003 N m at 10 N m), balanced by the moment of its linear axial and string
// forces about the deformed nodes (K δ about the mounted state is rotation-invariant to first
// order only, so the residual grows with the square of the load): the driver's torque falls
// 0.28 N m short of the load's. The co-rotated axial force removes it (next test).
#[test]
fn table_6_1_balances_on_flowing() {
    let drive = table_6_1::drive();
    let settings = SpeedLossConfig {
        torques: vec![10.0],
        ..SpeedLossConfig::default()
    };
    let mut model = FlowingBelt::new(&drive, &FlowingSettings::default()).unwrap();
    let (points, _) = speed_loss_sweep(&mut model, &settings, |_, _| {}).unwrap();
    for p in &points {
        assert_balanced(&format!("Table 6-1 flowing {} N m", p.torque), &p.report);
    }
}

// Table 6-1 at 10 and 30 N m on the flowing model with co-rotated elements
// (`AxialForce::CoRotated`: each element's force of the material law along its deformed chord,
// flowing::belt::model::Bar). The reference is the balance invariant itself, and the nodal model
// (the same K on material nodes, a second formulation) closes the same points to 0.3 % (next
// test). Measured 2026-12-05: 0.34 % / 0.27 % at 10 N m, 0.22 % / 0.21 % at 30 N m (torque /
// power; the linear model's 0.74 % / 0.92 % at 30 N m); with every free-node mode kept
// 0.11 % / 0.19 % at 30 N m. Per force group (net moment of the whole belt, steady state,
// 30 N m, co-rotated): contact 0.010 N m, β damping 0.006 N m, bending and the beam part of
// K_g(T0) −0.0002 N m, inertia 0.002 N m.
#[test]
fn table_6_1_balances_on_flowing_co_rotated() {
    let drive = table_6_1::drive();
    let settings = SpeedLossConfig {
        torques: vec![10.0, 30.0],
        ..SpeedLossConfig::default()
    };
    let flowing = FlowingSettings {
        axial_force: AxialForce::CoRotated,
        ..FlowingSettings::default()
    };
    let mut model = FlowingBelt::new(&drive, &flowing).unwrap();
    let (points, _) = speed_loss_sweep(&mut model, &settings, |_, _| {}).unwrap();
    assert_eq!(points.len(), 2);
    for p in &points {
        assert_balanced(
            &format!("Table 6-1 flowing co-rotated {} N m", p.torque),
            &p.report,
        );
    }
}

// Table 6-1 at 10 N m on the flowing model with the axial damping along the deformed chords
// (ViscousForce::Chord, Ribaric's projection (5.14)), against the balance invariants. Measured
// 2026-12-06 (h-bal4): torque 0.14 %, power −0.40 % (the linear damping's 0.24 % / −0.41 %).
// Not asserted: Table 6-1's speed loss. This damping gives Δω = 0.19079 rad/s, +2.4 % on
// Ribaric's 0.18630 rad/s, which the linear damping of (5.5) reproduces (the Kelvin–Voigt force
// on the chords' stretch rate is larger in the creep arcs than (5.5)'s on `v T_,s z`); the
// nodal model (material nodes, the Lagrangian rate) gives 0.19426 rad/s on the same sweep. It is
// selectable, not the default.
#[test]
fn table_6_1_balances_on_flowing_with_chord_damping() {
    let drive = table_6_1::drive();
    // the procedure's own sweep 0, 2, …, 10 N m
    let settings = SpeedLossConfig::default();
    let flowing = FlowingSettings {
        viscous_force: ViscousForce::Chord,
        ..FlowingSettings::default()
    };
    let mut model = FlowingBelt::new(&drive, &flowing).unwrap();
    let (points, _) = speed_loss_sweep(&mut model, &settings, |_, _| {}).unwrap();
    let p = points.iter().find(|p| p.torque == 10.0).unwrap();
    println!("Δω {} rad/s", p.delta_omega);
    assert_balanced("Table 6-1 flowing chord damping 10 N m", &p.report);
}

// Table 6-1 (Ribaric): the same steady points on the nodal model.
#[test]
fn table_6_1_balances_on_nodal() {
    let drive = table_6_1::drive();
    let settings = SpeedLossConfig {
        torques: vec![10.0, 30.0],
        // the study's nodal settings (drives::study::NodalConfig)
        window: 0.1,
        tolerance: 1e-3,
        ..SpeedLossConfig::default()
    };
    let mesh = BeltMesh {
        span_element: 0.45 / 40.0,
        arc_element: std::f64::consts::PI * 0.05 / 14.0,
        contact_margin_nodes: 1,
    };
    let mut nodal = NodalBelt::new(&drive, &mesh).unwrap();
    let (points, _) = speed_loss_sweep(&mut nodal, &settings, |_, _| {}).unwrap();
    for p in &points {
        assert_balanced(&format!("Table 6-1 nodal {} N m", p.torque), &p.report);
    }
}

// Table 6-1 (Ribaric): the same steady point at 10 N m on the ANCF belt with the study's
// settings (`drives::study::procedure_for`: its own step). Its spans' moments are taken about
// the lines of action of their section forces (`ancf::belt_drive::BeltDrive::span_force_lines`).
// Measured 2026-12-06: torque 0.15 % (driven pulley 0.015 N m), power 0.03 % (`flowmbd-belt
// speed-loss --model ancf --torques 0,10`: 0.09 %; with lines fitted through the centreline over
// the spans' middle halves 0.05 %).
#[test]
fn table_6_1_balances_on_ancf() {
    use drives::study::{ModelKind, ModelSettings, procedure_for};
    let drive = table_6_1::drive();
    let models = ModelSettings::default();
    let settings = procedure_for(
        ModelKind::Ancf,
        &SpeedLossConfig {
            torques: vec![10.0],
            ..SpeedLossConfig::default()
        },
        &models,
    );
    let mut ancf = drives::ancf_model::AncfBelt::new(&drive, &models.ancf).unwrap();
    let (points, _) = speed_loss_sweep(&mut ancf, &settings, |_, _| {}).unwrap();
    for p in &points {
        assert_balanced(&format!("Table 6-1 ANCF {} N m", p.torque), &p.report);
    }
}

/// The default fead drive at 800 rpm (`FeadConfig::default`) on `model`.
fn default_fead(model: FeadModel) -> FeadConfig {
    let mut c = FeadConfig {
        model,
        ..FeadConfig::default()
    };
    c.engine.speeds_rpm = vec![800.0];
    c
}

/// Run the one-point sweep `c` and check that it settles and closes both balances.
fn assert_steady_and_balanced(what: &str, c: &FeadConfig) {
    let s = run_fead(c, |_| {}).unwrap();
    let p = &s.points[0];
    println!("settled {} s, steady {}", p.settled_s, p.steady);
    assert!(p.steady);
    assert_balanced(what, &p.report);
}

/// The Pechstein–Gerstmayr drive of the shipped example, shortened for the test: load ramped
/// 0.1 → 0.4 s, 0.4 s settle after the crank's 0.3 s ramp; `element` \[m\], `step` \[s\].
fn pechstein_gerstmayr(model: FeadModel, element: f64, step: f64) -> FeadConfig {
    let text = include_str!("../../apps/belt/examples/pechstein-gerstmayr.toml");
    let mut c: FeadConfig = toml::from_str(text).unwrap();
    c.model = model;
    c.run.ramp = 0.3;
    c.run.settle = 0.4;
    c.run.step = step;
    c.run.window = 0.1;
    let load = belt::Signal::schedule(vec![(0.0, 0.0), (0.1, 0.0), (0.4, 25.0)]);
    if let belt::Motion::Load { torque, .. } = &mut c.drive.pulleys[1].motion {
        *torque = load;
    }
    let mesh = BeltMesh {
        span_element: element,
        arc_element: element,
        contact_margin_nodes: 1,
    };
    c.models.flowing.mesh = mesh;
    c.models.nodal.mesh = mesh;
    c
}

// Pechstein–Gerstmayr (Exudyn's improved belt): 25 N m + 2 N m s damper on the driven pulley;
// flowing model on 20 mm elements.
#[test]
fn pechstein_gerstmayr_balances_on_flowing() {
    let s = run_fead(
        &pechstein_gerstmayr(FeadModel::Flowing, 0.02, 2.5e-4),
        |_| {},
    )
    .unwrap();
    assert_balanced("Pechstein–Gerstmayr flowing", &s.points[0].report);
}

// The same with the axial damping along the deformed chords (ViscousForce::Chord). The whole
// shipped example with it (`fead --config apps/belt/examples/pechstein-gerstmayr.toml` plus
// `viscous_force = "chord"`, 10.5 mm loop, all modes), measured 2026-12-06: torque 0.002 %,
// power −0.083 %, driven 11.3075 rad/s (linear damping: 0.016 % / −0.083 %, 11.3075 rad/s).
#[test]
fn pechstein_gerstmayr_balances_on_flowing_with_chord_damping() {
    let mut c = pechstein_gerstmayr(FeadModel::Flowing, 0.02, 2.5e-4);
    c.models.flowing.viscous_force = ViscousForce::Chord;
    let s = run_fead(&c, |_| {}).unwrap();
    assert_balanced(
        "Pechstein–Gerstmayr flowing chord damping",
        &s.points[0].report,
    );
}

// The same on the ANCF belt (120 elements of the linear law, the example's 0.1 ms step).
#[test]
fn pechstein_gerstmayr_balances_on_ancf() {
    let s = run_fead(&pechstein_gerstmayr(FeadModel::Ancf, 0.02, 2.5e-4), |_| {}).unwrap();
    assert_balanced("Pechstein–Gerstmayr ANCF", &s.points[0].report);
}

/// The three-pulley example (`apps/belt/examples/fead-three-pulley.toml`) at 1500 rpm on
/// `model`, without its friction table: the layouts' default law (`belt::BeltContact::default`).
fn three_pulley(model: FeadModel) -> FeadConfig {
    let text = include_str!("../../apps/belt/examples/fead-three-pulley.toml");
    let mut c: FeadConfig = toml::from_str(text).unwrap();
    c.model = model;
    c.engine.speeds_rpm = vec![1500.0];
    c.drive.contact.friction = belt::BeltContact::default().friction;
    c
}

// A drive nobody tuned to: the three-pulley example (crank, back-side tensioner idler,
// alternator; `apps/belt/examples/fead-three-pulley.toml`) without its friction table, so with
// the layouts' default law (`tanh_slip` at 0.3 mm/s), at 1500 rpm on the ANCF belt with the fead
// study's settings for that law (`drives::fead::ancf_sharp_law_settings`). Measured
// 2026-12-07: with the 5 µm Newton position test alone the torque residual was 0.63 % at
// 0.5 mm/s and 3.06 % (power −3.11 %) at 0.3 mm/s: the last corrections moved slip velocities
// by up to 40 mm/s, 80 widths of the law's band; with the velocity test at four widths
// (`ancf::belt_drive::VTOL_PER_TRANSITION_WIDTH`) 0.02 % / 0.39 % at 0.5 mm/s, 0.01 % / 0.35 %
// at 0.3 mm/s (`flowmbd-belt fead`, 182 s of CPU). About 3 min of CPU: `--ignored`.
#[test]
#[ignore = "minutes: the ANCF belt at a sharp friction law over 0.5 s"]
fn three_pulley_balances_on_ancf_with_the_default_friction() {
    let c = three_pulley(FeadModel::Ancf);
    assert_steady_and_balanced("three-pulley 1500 rpm ANCF, default friction", &c);
}

// The same drive and point on the flowing belt's energy-consistent formulation
// (`energy_consistent` below: naturally straight bending, co-rotated axial force, chord
// damping, Lagrange's equations, 6 mm wraps). Measured 2026-12-07 at the default 0.3 mm/s:
// torque 0.39 %, power 0.14 % (1.36 W of 951 W), steady after 0.2 s, 50 s of CPU; at the
// earlier default 0.5 mm/s the same to the printed digits (43 s), and there over three 0.26 s
// windows from 0.2 to 0.98 s the power residual stays at 1.36–1.47 W. The default formulation
// misses here by 0.54 % / −4.5 % (its `balance_defect`); at 2500 rpm (21 m/s, 0.5 mm/s) this one
// misses too, 6.72 % / −1.10 % (issue 34 item 2, open).
#[test]
fn three_pulley_balances_on_the_energy_consistent_flowing_belt() {
    let mut c = three_pulley(FeadModel::Flowing);
    energy_consistent(&mut c.models.flowing);
    assert_steady_and_balanced("three-pulley 1500 rpm flowing, energy-consistent", &c);
}

// The same point on the nodal belt: fails. Measured 2026-12-07 at the then default 0.5 mm/s
// (window means of 0.26 s, about
// three loop passages, from 0.2 to 2.54 s): the power residual does not settle to a value but
// scatters from 3.9 to 25.9 W between windows at the fead study's ρ∞ = 0.8 (−9 to +33 W with
// 0.1 s windows to 3.1 s), about a mean of +16 W (1.7 % of the crank's 990 W); at ρ∞ = 0.6 the windows
// agree (15.4–18.6 W) on the same mean: the model's, not the window's. Not the step (0.125 ms:
// 18.3 W), the mesh (6 mm: 15.7, 12.3, 7.3 W) or the friction law (κ = 40: 12.8–17.1 W). Its
// linear parts are referenced to the travelling path: the damping forces `β K_e` on the
// co-rotated rate do +26 W of work on the material's travel (`v e_tᵀ Q_d`, not in the belt's
// reported dissipation), the rest −10 W. A naturally straight bending and a Kelvin–Voigt chord
// damping (branch `x-nodal-ec`, not merged) did not close it (−11 to −33 W). Issue 34 item 2,
// open: `--ignored`.
#[test]
#[ignore = "fails: the nodal belt's path-referenced linear forces work on the travel (issue 34)"]
fn three_pulley_balances_on_nodal() {
    let mut c = three_pulley(FeadModel::Nodal);
    c.run.rho_inf = 0.6;
    c.run.window = 0.26;
    c.run.settle = 0.8;
    assert_steady_and_balanced("three-pulley 1500 rpm nodal, default friction", &c);
}

// The same on the nodal model with the example's 120 elements and 0.1 ms step (about a minute
// of CPU: `--ignored`; the coarser 20 mm mesh stalls Newton as the load comes on).
#[test]
#[ignore]
fn pechstein_gerstmayr_balances_on_nodal() {
    let c = pechstein_gerstmayr(FeadModel::Nodal, 0.4 * std::f64::consts::PI / 120.0, 1e-4);
    let s = run_fead(&c, |_| {}).unwrap();
    assert_balanced("Pechstein–Gerstmayr nodal", &s.points[0].report);
}

// The default fead drive (six pulleys, back-side tensioner idler, crank fluctuation) at 800
// rpm, nodal model: window means over whole periods of the second engine order, the belt's
// Rayleigh damping in the power balance, span forces elastic plus viscous. Measured
// 2026-12-06: 0.14 % / 0.30 % (torque / power: power in 40.1 W = sliding 9.5 W + belt damping
// 25.8 W + 4.8 W).
//
// Not asserted: the flowing model on the same point. With the whole force measure (elastic plus
// the viscous force β EA Dε/Dt each element carries, flowing::belt::model::chord_viscous_forces)
// its torque residual fell from 1.5 % to 0.72 % (12 mm loop, all modes: 0.32 %); its power
// balance misses by −1.1 % (−1.9 % on the 12 mm loop): the pulleys take 21 W (35 W) out of the
// belt, and the power of its damping forces on the advected material is −10 W where the
// objective Kelvin–Voigt dissipation of its axial forces, Σ N_v² l/(β EA), is +25–30 W and the
// nodal belt's damping dissipates 25.8 W. The flowing model's damping and linear elastic forces
// do net work on the material flowing through the stationary mesh (issue 34, open): its crank
// torque is 0.7–0.9 N m below the nodal model's, which is also what separates the two models'
// slack spans (drives/tests/fead_steady_means.rs).
//
// Diagnosis (h-bal3, 2026-12-06; flowing::belt::flowing_system module documentation and its
// energy tests): the free, undamped flowing belt does not conserve energy under Ribaric's
// projection (5.14) (test `the_free_undamped_belt_conserves_its_energy_with_ribaric_projection`,
// ignored: dE/dt = −0.39 W at a state where Lagrange's equations give 1e-12 W). At this point
// (800 rpm, window means) the e_t row's elastic forces do +32.7 W on the flowing material
// (linear part v (f0ᵀ T_,s z − e_tᵀ K δ), 19 W of it on the alternator's wrap; −5.6 W second
// order), the damping forces +10.8 W (so the reported belt damping is −10.8 W) where their
// dissipation 2R is 29.8 W. Lagrange's equations of the same model
// (FlowingBelt::with_lagrange_equations) close the power balance to 0.65 % (0.04 % on 4 mm wraps)
// with the crank torque of the nodal model (19.08 against 19.00 N m), but put the same defect on
// the reference node's tangential balance (window means: elastic bᵀ(f0 − Kδ) = 4.2 N, damping
// bᵀg_d + ∂R/∂v = 6.5 N; times the crank's 75 mm, 0.80 N m): the crank's torque residual is then
// 4.8 % (Table 6-1 at 10 N m: 0.76 % / 0.03 %). Neither form meets 0.5 % on both balances here;
// the open fix is relabelling-invariant elastic and viscous forces (along the deformed chord).
#[test]
fn default_fead_balances_on_nodal() {
    assert_steady_and_balanced("fead 800 rpm nodal", &default_fead(FeadModel::Nodal));
}

// The same on the ANCF belt (the fead study's ANCF settings). The alternator → tensioner span
// is 57 mm long between pulleys of 28 and 35 mm: the moments of the two bending boundary layers
// (`√(EI/T)` = 8 mm) leave a shear force over the whole span, so its force does not act along
// its centreline. Measured 2026-12-06: with the lines fitted through the centreline over the
// middle half the torque residual was 0.66 % (alternator 0.12 N m, tensioner −0.10 N m); with
// the lines of the section forces (`BeltDrive::span_force_lines`) 0.18 %, power 0.20 %.
#[test]
fn default_fead_balances_on_ancf() {
    assert_steady_and_balanced("fead 800 rpm ANCF", &default_fead(FeadModel::Ancf));
}

// Issue 34 item 2 on the flowing model's default formulation (Ribaric (5.14), linear axial and
// damping forces): fails. Measured 2026-12-06 (h-bal4, window means at 800 rpm): torque 0.72 %,
// power −1.06 % (−16.3 W of 1535 W). Every other formulation of the flowing module misses as
// well (torque / power): co-rotated axial force 0.72 / −2.83 %; chord damping
// (ViscousForce::Chord) 0.98 / −1.63 %; Lagrange's equations 4.81 / 0.65 %, with chord damping
// 3.15 / 0.71 %; every free-node mode kept 0.27 / −1.88 %; 4 mm wraps 5.50 / 1.85 %.
// What remains is the elastic forces' work on the slide, bᵀ(f0 − K δ) (window means on the
// default loop: pre-tension −24.2 N and the string part of K_g(T0) +25.6 N, cancelling to
// 1.4 N, 0.1 N on 4 mm wraps; axial −0.4 N; bending +4.0 N, 4.4 N on 4 mm wraps): the bending
// stiffness of Ribaric (5.5) is stress-free on the mounted polygon (the belt's natural
// curvature follows the path), and a curvature reference that jumps by 1/R at the tangent points
// is not invariant under the material's slide, in the continuum as on the mesh (EI/R² = 33 N on
// the 28 mm pulleys). With EI/100 the default formulation closes both (next test).
#[test]
#[ignore = "fails: the path-referenced bending of Ribaric (5.5) does work on the slide (issue 34)"]
fn default_fead_balances_on_flowing() {
    assert_steady_and_balanced("fead 800 rpm flowing", &default_fead(FeadModel::Flowing));
}

// The default fead drive at 800 rpm on the flowing model's energy-consistent formulation: a
// naturally straight belt (co-rotated bending, BendingForce::CoRotated, undamped), the
// Kelvin–Voigt axial force along the deformed chords (ViscousForce::Chord) and Lagrange's
// equations of (s_b, z) (BeltEquations::Lagrange: dE/dt = Vᵀ F − 2R for any mesh), on 6 mm wrap
// elements. The invariants of issue 34 item 2 hold: measured 2026-12-07, torque 0.41 %, power
// 0.43 % (8 mm wraps: 0.39 / 0.55 %; 4 mm: 0.46 / 0.11 %; 12 mm: 1.53 / 0.51 %), with 12
// free-node modes; with every mode (the study's default since h-v2) 0.37 / 0.43 %. Not the
// default: at 1500–3500 rpm its torque residual is 0.6–1.2 % (power ≤ 0.31 %), on Table 6-1 1.4 %
// (BENCHMARKS, "an energy-consistent flowing belt"), and it costs 28 s against 1.5 s.
#[test]
fn default_fead_balances_on_the_energy_consistent_flowing_belt() {
    let mut c = default_fead(FeadModel::Flowing);
    energy_consistent(&mut c.models.flowing);
    assert_steady_and_balanced("fead 800 rpm flowing, energy-consistent", &c);
}

/// The flowing belt's energy-consistent formulation (BENCHMARKS, "An energy-consistent flowing
/// belt"): naturally straight (co-rotated bending, undamped), each element's force of the
/// material law along its deformed chord (co-rotated axial force) with the Kelvin–Voigt force on
/// the chord's material rate (chord damping), Lagrange's equations of (s_b, z), 6 mm wrap
/// elements (on the small pulleys of Table 6-1 and the FEAD drive: they resolve the lift-off).
fn energy_consistent(f: &mut FlowingSettings) {
    f.bending = BendingForce::CoRotated;
    f.axial_force = AxialForce::CoRotated;
    f.viscous_force = ViscousForce::Chord;
    f.equations = BeltEquations::Lagrange;
    f.mesh.arc_element = 0.006;
}

// Table 6-1 at 10 N m on the energy-consistent formulation (previous function). Measured
// 2026-12-07 (`speed-loss` with `torques = [0, 10]`): torque 0.15 %, power 0.05 %, Δω 0.19233
// rad/s (the nodal model 0.19443, the ANCF belt 0.18760). With the linear axial force of
// Ribaric (5.5) instead the torque residual was 1.40 %: the spans' lines of action sat 40–60 %
// short of the lift-off offset `EI/(R T)` of a naturally straight belt.
#[test]
fn table_6_1_balances_on_the_energy_consistent_flowing_belt() {
    let drive = table_6_1::drive();
    let settings = SpeedLossConfig {
        torques: vec![10.0],
        ..SpeedLossConfig::default()
    };
    let mut f = FlowingSettings::default();
    energy_consistent(&mut f);
    let mut model = FlowingBelt::new(&drive, &f).unwrap();
    let (points, _) = speed_loss_sweep(&mut model, &settings, |_, _| {}).unwrap();
    for p in &points {
        assert_balanced(
            &format!("Table 6-1 flowing energy-consistent {} N m", p.torque),
            &p.report,
        );
    }
}

// The Pechstein–Gerstmayr drive on the energy-consistent formulation with the shipped example's
// mesh and step (10.5 mm loop, every mode, 0.1 ms; the test's shortened ramp and settle).
// Measured 2026-12-07 on the whole example (`fead --config` with the four [models.flowing] keys
// of `energy_consistent`, its own 10.5 mm wraps: the 0.1 m pulleys need no finer ones): torque
// 0.35 %, power 0.25 %, driven 11.3042 rad/s (Exudyn refined 11.319), spans 662.9 / 187.2 N.
// On the test's coarser 20 mm mesh with 6 mm wraps at 0.25 ms its Newton matrix turns singular
// at t = 0.42 s (the naturally straight belt's undamped bending: BENCHMARKS, "a naturally
// straight, co-rotated bending element").
// Several minutes of CPU: `--ignored`.
#[test]
#[ignore = "heavy: the example's 10.5 mm loop at 0.1 ms on the energy-consistent formulation"]
fn pechstein_gerstmayr_balances_on_the_energy_consistent_flowing_belt() {
    let mut c = pechstein_gerstmayr(FeadModel::Flowing, 0.4 * std::f64::consts::PI / 120.0, 1e-4);
    energy_consistent(&mut c.models.flowing);
    c.models.flowing.mesh.arc_element = 0.4 * std::f64::consts::PI / 120.0;
    // the example states Ribaric's rates for its own figures; the measurement above took the
    // default, the chords' rates with its regularised law
    c.models.flowing.contact_velocity = ContactVelocity::Auto;
    let s = run_fead(&c, |_| {}).unwrap();
    assert_balanced(
        "Pechstein–Gerstmayr flowing energy-consistent",
        &s.points[0].report,
    );
}

// The default fead drive with a belt of a hundredth of the bending stiffness (EI = 2.6e-4
// N m²), default flowing formulation: the balance invariants hold once the bending reference's
// work on the slide (previous test) is small. Measured 2026-12-06 (h-bal4): torque 0.31 %, power
// −0.27 % (12 free-node modes; every mode, the study's default since h-v2: 0.32 / −0.23 %). The other forms still miss at EI/100 (Lagrange's equations 4.13 % / 0.83 %, chord
// damping 0.33 % / −0.79 %): the smaller slide defects remain, and this pass may be in part
// their cancellation.
#[test]
fn default_fead_with_a_thin_belt_balances_on_flowing() {
    let mut c = default_fead(FeadModel::Flowing);
    c.drive.belt.ei /= 100.0;
    assert_steady_and_balanced("fead 800 rpm flowing EI/100", &c);
}
