//! Multi-ribbed belts in the time-stepped models (issue 36 item 3): every model contacts each
//! pulley with the law of [`belt::Drive::wrap_friction_law`], `μ/sin(β/2)` where the ribs run
//! in a grooved pulley and `μ` on a flat back-side pulley (Johnson, *Contact Mechanics* §8.6),
//! and the report measures each wrap against that pulley's `μ`.
//!
//! References: the wedge factor `1/sin(β/2)` in closed form; the Euler–Eytelwein capacity of
//! the fixed-centre two-pulley drive ([`drives::euler_eytelwein_capacity`], closed form) with
//! `μ` and with `μ/sin(β/2)`; the capstan law `T_tight/T_slack = e^{μ' φ_slip}` on the slip
//! arcs.

use belt::{Drive, Layout, Motion, Pulley, Ribs, Role, Section, Signal, WrapSide};
use contact::friction::{FrictionLaw, FrictionSpec};
use drives::ancf_model::{AncfBelt, AncfConfig};
use drives::{SpeedLossConfig, SpeedLossPoint, euler_eytelwein_capacity, speed_loss_sweep};
use flowing::belt::{BeltMesh, FlowingBelt, FlowingSettings, NodalBelt};

/// The PK rib (ISO 9981, SAE J1459): 40° included angle.
fn pk_ribs() -> Ribs {
    Ribs {
        count: 6,
        wedge_angle: 40f64.to_radians(),
    }
}

/// The friction law of these tests, stated here (not the default contact's, which another
/// change may retune): tanh with μ = 0.3, κ = 40 s/m (Ribaric (6.2)'s form).
const LAW: FrictionSpec = FrictionSpec::Tanh {
    mu: 0.3,
    kappa: 40.0,
};

/// Crank, alternator (both grooved) and a back-side idler on the slack span (the drive of
/// `drives::simulation`'s example, without the tensioner arm), the Table 6-1 belt at 300 N
/// with `ribs`.
fn with_back_side(ribs: Option<Ribs>) -> Drive {
    let crank = Motion::speed(Signal::schedule(vec![(0.0, 0.0), (0.02, 40.0)]));
    let mut layout = Layout::new(
        vec![
            Pulley::new("crank", [0.0, 0.0], 0.06, WrapSide::Inside, crank),
            Pulley::new(
                "alternator",
                [0.3, 0.05],
                0.03,
                WrapSide::Inside,
                Motion::load(2e-3, Signal::constant(1.5)),
            ),
            Pulley::new(
                "idler",
                [0.15, -0.035],
                0.03,
                WrapSide::Outside,
                Motion::idler(1e-4),
            ),
        ],
        Section::default(),
        300.0,
    );
    layout.belt.ribs = ribs;
    layout.contact.friction = LAW;
    layout.resolve().unwrap()
}

// (c) Every model's per-pulley law: with 40° ribs μ/sin 20° = 0.3 · 2.9238 = 0.8771 on the two
// grooved pulleys and the plain μ = 0.3 on the back-side idler (closed form; the idler's law is
// the contact's law itself). A flat belt contacts every pulley with the contact's law exactly
// (factor 1: the same bits, so a flat belt's results are unchanged).
#[test]
fn every_model_scales_mu_on_grooved_pulleys_only() {
    let factor = 1.0 / 20f64.to_radians().sin();
    assert!((factor - 2.923_804_400_163_087).abs() < 1e-12);
    for ribs in [Some(pk_ribs()), None] {
        let drive = with_back_side(ribs);
        let expect = |k: usize| match (ribs, drive.pulleys()[k].side) {
            (Some(_), WrapSide::Inside) => 0.3 * factor,
            _ => 0.3,
        };
        let flowing = FlowingBelt::new(&drive, &FlowingSettings::default()).unwrap();
        let nodal = NodalBelt::new(
            &drive,
            &BeltMesh {
                span_element: 0.02,
                arc_element: 0.01,
                contact_margin_nodes: 1,
            },
        )
        .unwrap();
        let ancf = AncfBelt::new(
            &drive,
            &AncfConfig {
                elements: 60,
                ..Default::default()
            },
        )
        .unwrap();
        for k in 0..3 {
            let laws = [
                ("flowing", *flowing.friction_law(k)),
                ("nodal", *nodal.friction_law(k)),
                ("ancf", *ancf.belt_drive().friction_law(k)),
            ];
            for (name, law) in laws {
                let mu = law.coefficient();
                assert!(
                    (mu - expect(k)).abs() < 1e-12,
                    "{name}, pulley {k}, ribs {ribs:?}: μ {mu}"
                );
                assert_eq!(law, drive.wrap_friction_law(k), "{name}, pulley {k}");
                // the regularisation is the contact's: κ unchanged
                assert!(matches!(law, FrictionSpec::Tanh { kappa, .. } if kappa == 40.0));
                if ribs.is_none() || k == 2 {
                    assert_eq!(
                        law, LAW,
                        "{name}, pulley {k}: the contact's law, bit for bit"
                    );
                }
            }
        }
        // the design study's capacity check takes the same coefficients
        let design = drives::fead_design::wrap_friction(&drive);
        assert_eq!(design, (0..3).map(expect).collect::<Vec<_>>());
    }
}

/// Ribaric's Table 6-1 drive (two pulleys of 50 mm, π wraps, T0 = 310 N) with [`LAW`] and
/// `ribs`.
fn table_6_1(ribs: Option<Ribs>) -> Drive {
    let mut layout = drives::table_6_1::layout();
    layout.belt.ribs = ribs;
    layout.contact.friction = LAW;
    layout.resolve().unwrap()
}

fn sweep(drive: &Drive, torques: Vec<f64>, omega: f64) -> Vec<SpeedLossPoint> {
    let mut model = FlowingBelt::new(drive, &FlowingSettings::default()).unwrap();
    let settings = SpeedLossConfig {
        omega_driver: omega,
        torques,
        ..Default::default()
    };
    let (points, _) = speed_loss_sweep(&mut model, &settings, |_, _| {})
        .unwrap_or_else(|f| panic!("sweep failed: {} (points {:?})", f.error, f.points));
    for p in &points {
        println!(
            "ribs {}: M = {:.2} N m, Δω {:.4} rad/s, T {:.1}/{:.1} N, slip arcs {:.3}/{:.3} rad, \
             gross slip {:?}",
            drive.belt().ribs.is_some(),
            p.torque,
            p.delta_omega,
            p.report.tension_tight(),
            p.report.tension_slack(),
            p.report.slip_arc(Role::Driver),
            p.report.slip_arc(Role::Driven),
            p.gross_slip.as_ref().map(|g| &g.criterion),
        );
    }
    points
}

// (b) The wedge in the time simulation (flowing model, Table 6-1 drive at 62.8 rad/s, μ = 0.3):
// the load is the mean of the flat belt's Euler–Eytelwein capacity (closed form with μ = 0.3)
// and the ribbed belt's (μ' = μ/sin 20° = 0.877). The flat belt cannot carry it: the driven
// pulley slides as a whole and runs away (gross slip, the sweep's result); the ribbed belt
// carries it in a steady state with adhesion on both wraps, and each wrap's span tension ratio
// follows the capstan law with μ' on its slip arc, |ln(T_in/T_out)| = μ' φ_slip within 5 % in
// the exponent (the flowing model's bound for the flat belt, tests/tests/belt_drive_outputs.rs:
// the nodal penalty's pressure is not T/R near the tangent points). With the flat μ the same
// slip arc would give a third of the exponent.
#[test]
fn ribs_carry_a_torque_the_flat_belt_cannot() {
    let omega = 62.8;
    let (flat, ribbed) = (table_6_1(None), table_6_1(Some(pk_ribs())));
    let mu_eff = 0.3 / 20f64.to_radians().sin();
    assert!((ribbed.wrap_friction_coefficients()[1] - mu_eff).abs() < 1e-12);
    let (c_flat, c_ribbed) = (
        euler_eytelwein_capacity(&flat, omega),
        euler_eytelwein_capacity(&ribbed, omega),
    );
    let load = 0.5 * (c_flat + c_ribbed);
    println!("capacities: flat {c_flat:.2} N m, ribbed {c_ribbed:.2} N m; load {load:.2} N m");
    assert!(c_ribbed > 1.5 * c_flat, "{c_flat} {c_ribbed}");

    let flat_points = sweep(&flat, vec![0.0, load], omega);
    let g = flat_points[1]
        .gross_slip
        .as_ref()
        .expect("the flat belt slides at the ribbed belt's load");
    assert_eq!(g.name, "driven");

    let ribbed_points = sweep(&ribbed, vec![0.0, load], omega);
    let p = &ribbed_points[1];
    assert!(p.gross_slip.is_none(), "{:?}", p.gross_slip);
    assert!(p.linearisation.is_none(), "{:?}", p.linearisation);
    assert_eq!(p.report.gross_slip(), None);
    let driven = &p.report.pulleys[1];
    assert!(
        (driven.torque_n_m - load).abs() < 1e-2 * load,
        "driven torque {} N m vs load {load}",
        driven.torque_n_m
    );
    let tc = ribbed.belt().mass_per_length * (omega * 0.05).powi(2);
    for q in &p.report.pulleys {
        let ln = ((q.tension_in_n - tc) / (q.tension_out_n - tc)).ln().abs();
        let capstan = mu_eff * q.slip_arc_rad;
        println!(
            "  {}: T_in/T_out = {:.3}, e^(μ' φ_slip) = {:.3} (φ_slip {:.3} of {:.3} rad, \
             adhesion {:.3} rad)",
            q.name,
            q.tension_in_n / q.tension_out_n,
            capstan.exp(),
            q.slip_arc_rad,
            q.contact_arc_rad,
            q.adhesion_arc_rad
        );
        assert!(
            (ln - capstan).abs() <= 0.05 * ln,
            "{}: ln ratio {ln} vs μ' φ_slip {capstan}",
            q.name
        );
        assert!(q.adhesion_arc_rad > 0.2 * q.contact_arc_rad, "{q:?}");
    }
}
