//! The string wrapped on two pulleys with variable-size contact (Ribaric (4.10), (4.11),
//! (4.31)–(4.40)).
#![allow(clippy::needless_range_loop)] // index loops mirror the matrix equations

use flowing::contact::{ContactEvent, candidates};
use flowing::{
    AxialMotion, ContactConfig, ContactString, DerivativeMethod, PulleyObstacle, StringConfig,
    StringMesh, simulate_contact,
};
use mbd_core::integrators::State;

const TOP: f64 = 0.015;
const R: f64 = 0.25;

fn mesh(n: usize) -> StringMesh {
    let p = StringConfig {
        length: 1.2,
        ..StringConfig::default()
    };
    StringMesh::uniform(p, n).unwrap()
}

fn pulleys() -> [PulleyObstacle; 2] {
    [
        PulleyObstacle {
            center_x: 0.1,
            top: TOP,
            radius: R,
        },
        PulleyObstacle {
            center_x: 1.1,
            top: TOP,
            radius: R,
        },
    ]
}

fn nodal(n: usize, speed: f64) -> (StringMesh, ContactString) {
    let m = mesh(n);
    let c = candidates(&m, &pulleys(), 0.08).unwrap();
    let s = ContactString::nodal(
        &m,
        c,
        DerivativeMethod::default(),
        AxialMotion::Constant { speed },
        None,
    )
    .unwrap();
    (m, s)
}

// Reference: geometry of a string over a convex obstacle. Contact spans from the tangent point of
// the straight segment from the anchor to the pulley top; in the parabolic approximation the
// tangent point is at x_c − a with a = x_c − √(x_c² − 2 d R) = 0.05 m. Contact forces are
// compressive, active nodes lie on the surface and no inactive node penetrates.
#[test]
fn static_wrap_matches_tangent_geometry() {
    let (_, mut s) = nodal(59, 0.0);
    let y = s.static_equilibrium().unwrap();
    let a = 0.1 - (0.01f64 - 2.0 * TOP * R).sqrt();
    let state = State::new(0.0, y.clone(), vec![0.0; y.len()]);
    let p = s.contact_forces(&state).unwrap();
    for (c, cand) in s.candidates.iter().enumerate() {
        if s.active[c] {
            assert!(s.gap(c, &y).abs() < 1e-12);
            assert!(p[c] > 0.0, "node {} force {}", cand.node, p[c]);
            let d = (cand.x - if cand.pulley == 0 { 0.1 } else { 1.1 }).abs();
            assert!(
                d <= a + 0.02 + 1e-12,
                "active node at distance {d} > a = {a}"
            );
        } else {
            assert!(s.gap(c, &y) > -1e-12);
        }
    }
    let n_active = s.active.iter().filter(|a| **a).count();
    // a = 0.05 m, h = 0.02 m: 3 nodes per pulley from the tangent point to the top (±1).
    assert!((4..=8).contains(&n_active), "{n_active} active");
    // Total vertical contact force balances the string's kinks: Σp = 2 T sin(slope) ≈ 2·T·a/R.
    let total: f64 = p.iter().sum();
    let expect = 2.0 * 1000.0 * (a / R);
    assert!(
        (total - expect).abs() < 0.1 * expect,
        "Σp = {total}, expected ≈ {expect}"
    );
}

fn pluck(s: &ContactString, y: &[f64], amp: f64) -> Vec<f64> {
    // Upward triangular pluck of the span, added to the nodal static deflection (nodal form).
    let mut u = y.to_vec();
    let n = u.len();
    let h = 1.2 / (n + 1) as f64;
    for (j, uj) in u.iter_mut().enumerate() {
        let x = (j + 1) as f64 * h;
        if x > 0.1 && x < 1.1 {
            *uj += amp * (1.0 - ((x - 0.6) / 0.5).abs());
        }
    }
    let _ = s;
    u
}

// Reference: energy balance. Without damping and load the total energy is conserved except for the
// kinetic energy removed by plastic impacts, which is reported per event: E(t) + Σ losses = E(0) to
// integrator tolerance. Contact nodes stay on the pulley (gap ≈ 0) while their force is compressive.
#[test]
fn wrapped_string_conserves_energy_and_keeps_active_nodes_on_pulley() {
    let (_, mut s) = nodal(59, 0.0);
    let y = s.static_equilibrium().unwrap();
    let u0 = pluck(&s, &y, 0.04);
    let n = u0.len();
    let state0 = State::new(0.0, u0, vec![0.0; n]);
    // A 4 cm upward pluck lifts the string off the pulley tops: release events must happen.
    let e0 = s.energy(&state0.q, &state0.v, 0.0);
    let mut worst_gap: f64 = 0.0;
    let mut worst_force: f64 = 0.0;
    let mut samples = Vec::new();
    let run = simulate_contact(
        &mut s,
        state0,
        0.06,
        &ContactConfig::default(),
        |sys, st| {
            for c in 0..sys.candidates.len() {
                if sys.active[c] {
                    worst_gap = worst_gap.max(sys.gap(c, &st.q).abs());
                }
            }
            let p = sys.contact_forces(st).unwrap();
            for c in 0..sys.candidates.len() {
                if sys.active[c] {
                    worst_force = worst_force.min(p[c]);
                }
            }
            samples.push((st.t, sys.energy(&st.q, &st.v, 0.0)));
        },
    )
    .unwrap();
    let releases = run.events.iter().filter(|e| !e.activated).count();
    let contacts = run.events.iter().filter(|e| e.activated).count();
    assert!(releases > 0, "no lift-off: {:?}", run.events);
    // At an event time the observer sees the state before and after the impact: accept the
    // balance with the losses strictly before t or up to and including t.
    let loss = |t: f64, ev: &[ContactEvent], incl: bool| {
        ev.iter()
            .filter(|e| e.t < t || (incl && e.t == t))
            .map(|e| e.impact_loss)
            .sum::<f64>()
    };
    for (t, e) in &samples {
        let b1 = (e + loss(*t, &run.events, false) - e0).abs();
        let b2 = (e + loss(*t, &run.events, true) - e0).abs();
        assert!(
            b1.min(b2) < 1e-6 * e0,
            "t = {t}: E = {e}, E0 = {e0}, imbalance {}",
            b1.min(b2)
        );
    }
    assert!(contacts > 0, "the string must land on the pulleys again");
    assert!(
        worst_gap < 1e-9,
        "active node left the pulley by {worst_gap}"
    );
    assert!(worst_force > -1e-6, "tensile active contact {worst_force}");
    eprintln!(
        "releases {releases}, contacts {contacts}, E0 {e0}, final E {}",
        samples.last().unwrap().1
    );
}

// Reference: second formulation — with all free modes kept, the Craig–Bampton form (4.11) spans
// the nodal space, so its static wrap and its transient (events included) equal the nodal model
// (4.10) (notes STR-7).
#[test]
fn craig_bampton_with_all_modes_equals_nodal_model() {
    let m = mesh(39);
    let c = candidates(&m, &pulleys(), 0.08).unwrap();
    let nf = 39 - c.len();
    let mut nod = ContactString::nodal(
        &m,
        c.clone(),
        DerivativeMethod::default(),
        AxialMotion::Constant { speed: 0.0 },
        None,
    )
    .unwrap();
    let mut cb = ContactString::craig_bampton(
        &m,
        c,
        nf,
        DerivativeMethod::default(),
        AxialMotion::Constant { speed: 0.0 },
        None,
    )
    .unwrap();
    let yn = nod.static_equilibrium().unwrap();
    let yc = cb.static_equilibrium().unwrap();
    let uc = cb.deflection(&yc);
    for i in 0..39 {
        assert!(
            (yn[i] - uc[i]).abs() < 1e-10,
            "node {i}: {} vs {}",
            yn[i],
            uc[i]
        );
    }
    assert_eq!(nod.active, cb.active);
    let u0 = pluck(&nod, &yn, 0.03);
    let y0c = flowing::contact::coordinates_of(&cb, m.mass.as_ref(), &u0).unwrap();
    let s = ContactConfig::default();
    let rn = simulate_contact(
        &mut nod,
        State::new(0.0, u0, vec![0.0; 39]),
        0.03,
        &s,
        |_, _| {},
    )
    .unwrap();
    let rc = simulate_contact(
        &mut cb,
        State::new(0.0, y0c, vec![0.0; 39]),
        0.03,
        &s,
        |_, _| {},
    )
    .unwrap();
    let uc = cb.deflection(&rc.state.q);
    let scale = rn.state.q.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    for i in 0..39 {
        assert!(
            (rn.state.q[i] - uc[i]).abs() < 1e-5 * scale,
            "node {i}: {} vs {}",
            rn.state.q[i],
            uc[i]
        );
    }
    assert_eq!(rn.events.len(), rc.events.len());
}

// Reference: the travelling wrapped string (4.40) at constant speed conserves
// H = ½ẏᵀTᵀMTẏ + ½yᵀ(TᵀKT + ẋ²TᵀMT_,ss)y apart from the plastic impact losses, because
// TᵀMT_,s is skew for FE-consistent derivatives (gyroscopic forces do no work).
#[test]
fn travelling_wrapped_string_energy_balance() {
    let v = 10.0;
    let m = mesh(39);
    let c = candidates(&m, &pulleys(), 0.08).unwrap();
    let mut s = ContactString::craig_bampton(
        &m,
        c,
        12,
        DerivativeMethod::default(),
        AxialMotion::Constant { speed: v },
        None,
    )
    .unwrap();
    for i in 0..s.dim() {
        for j in 0..s.dim() {
            assert!((s.mx_r[(i, j)] + s.mx_r[(j, i)]).abs() < 1e-9);
        }
    }
    let y = s.static_equilibrium().unwrap();
    let mut v0 = vec![0.0; y.len()];
    v0[0] = 0.5; // kick the first span mode
    let e0 = s.energy(&y, &v0, v);
    let mut samples = Vec::new();
    let run = simulate_contact(
        &mut s,
        State::new(0.0, y, v0),
        0.04,
        &ContactConfig::default(),
        |sys, st| {
            samples.push((st.t, sys.energy(&st.q, &st.v, v)));
        },
    )
    .unwrap();
    let loss = |t: f64, incl: bool| {
        run.events
            .iter()
            .filter(|e| e.t < t || (incl && e.t == t))
            .map(|e| e.impact_loss)
            .sum::<f64>()
    };
    for (t, e) in &samples {
        let b = (e + loss(*t, false) - e0)
            .abs()
            .min((e + loss(*t, true) - e0).abs());
        assert!(b < 1e-6 * e0, "t = {t}: imbalance {b} of {e0}");
    }
}
