//! Unilateral constraints by an active set on generalized-α ([`ActiveSetStepper`]): point masses
//! above a rigid floor, `g_c = y_c ≥ 0`. References: free fall (touch-down at `√(2h/g)`), the
//! perfectly plastic impact of the index-3 position constraint (the mass stops on the floor and
//! rests with the contact force `m g`), and the release when a growing upward force exceeds the
//! weight (lift-off at `F(t*) = m g`, then `y = (g/3T)(t − t*)³` for `F = 2 m g t/T`).

use mbd_core::SecondOrderSystem;
use mbd_core::integrators::{
    ActiveSetStepper, ActiveSetSystem, AlphaConfig, State, UnilateralConstraints, UnilateralEval,
};

use crate::support;
use support::PointMasses;

const G: f64 = 9.81;

/// Point masses moving vertically (`q = y`), gravity and an upward force `2 m g t/lift` on each
/// (none when `lift = ∞`).
fn masses(m: Vec<f64>, lift: f64) -> PointMasses {
    PointMasses {
        m,
        dim: 1,
        g: G,
        lift,
    }
}

/// The floor `y = 0` under every mass.
struct Floor(usize);

impl UnilateralConstraints for Floor {
    fn n_candidates(&self) -> usize {
        self.0
    }
    fn candidate_name(&self, c: usize) -> String {
        format!("mass {c} on the floor")
    }
    fn gap(&self, _t: f64, q: &[f64], c: usize) -> f64 {
        q[c]
    }
    fn row(&self, _t: f64, q: &[f64], _v: &[f64], c: usize, row: &mut UnilateralEval) {
        row.gap = q[c];
        row.jacobian.push((c, 1.0));
    }
}

fn params() -> AlphaConfig {
    AlphaConfig {
        h: 1e-4,
        rho_inf: 0.6,
        ..Default::default()
    }
}

// Reference: free fall to touch-down at √(2h/g) (the nearer mass first), the plastic impact
// (each mass stays on the floor, at rest) and the resting contact forces m g.
#[test]
fn falling_masses_land_in_order_and_rest_on_the_floor() {
    let sys = masses(vec![2.0, 0.5], f64::INFINITY);
    let floor = Floor(2);
    let heights = [0.02, 0.01];
    let state0 = State::new(0.0, heights.to_vec(), vec![0.0; 2]);
    let mut st = ActiveSetStepper::new(&sys, &floor, state0, params()).unwrap();
    let mut landed = [None; 2];
    let mut order = Vec::new();
    st.advance_to(0.15, &mut |s| {
        for &c in s.active {
            if landed[c].is_none() {
                landed[c] = Some(s.state.t);
                order.push(c);
            }
        }
    })
    .unwrap();
    assert_eq!(order, vec![1, 0], "the lower mass lands first");
    for c in 0..2 {
        let t_hit = (2.0 * heights[c] / G).sqrt();
        let t1 = landed[c].unwrap();
        assert!(
            t1 >= t_hit && t1 <= t_hit + params().h + 1e-12,
            "mass {c} lands at {t1} s, free fall {t_hit} s"
        );
    }
    let last = st.last_step();
    assert_eq!(st.active(), &[1, 0]);
    for (k, &c) in last.active.iter().enumerate() {
        assert!(last.state.q[c].abs() < 1e-12 && last.state.v[c].abs() < 1e-9);
        let w = sys.m[c] * G;
        assert!(
            (last.forces[k] - w).abs() < 1e-9 * w,
            "mass {c}: {} N vs {w} N",
            last.forces[k]
        );
    }
    // the stacked model: the floor rows follow the model's (none), named by the candidates
    let s: &ActiveSetSystem<_, _> = st.system();
    assert_eq!(s.n_c(), 2);
    assert_eq!(s.constraint_name(0), "mass 1 on the floor");
    // after each impact the index-3 multiplier oscillates (decaying with ρ∞ < 1): the masses
    // are released and re-taken a few times before they rest
    let (retakes, restarts) = st.changes();
    assert!(
        retakes >= 2 && restarts >= retakes,
        "{retakes} retakes, {restarts} restarts"
    );
    assert!(st.stats().steps >= 1500);
}

// Reference: a resting mass lifted by F = 2 m g t/T leaves the floor when F = m g (t* = T/2;
// released in the step in which the contact force turns tensile) and then rises as
// y = (g/3T)(t − t*)³.
#[test]
fn lifted_mass_is_released_when_the_force_turns_tensile() {
    let lift = 0.2;
    let sys = masses(vec![1.5], lift);
    let floor = Floor(1);
    // resting on the floor: the floor is active before the first step's end
    let state0 = State::new(0.0, vec![0.0], vec![0.0]);
    let mut st = ActiveSetStepper::new(&sys, &floor, state0, params()).unwrap();
    let mut release = None;
    let mut was_active = false;
    st.advance_to(lift, &mut |s| {
        if !s.active.is_empty() {
            was_active = true;
            // contact force m g − F(t) while on the floor
            let expect = 1.5 * G * (1.0 - 2.0 * s.state.t / lift);
            assert!((s.forces[0] - expect).abs() < 1e-6 * 1.5 * G);
            if s.forces[0] < 0.0 && release.is_none() {
                release = Some(s.state.t);
            }
        }
    })
    .unwrap();
    assert!(was_active, "the resting mass is held by the floor");
    let t_rel = release.expect("released");
    let t_star = 0.5 * lift;
    assert!(t_rel >= t_star && t_rel <= t_star + params().h + 1e-12);
    assert!(st.active().is_empty());
    let y = st.state().q[0];
    let exact = G / (3.0 * lift) * (lift - t_star).powi(3);
    assert!(
        (y - exact).abs() < 5e-3 * exact,
        "y(T) = {y} m, exact {exact} m"
    );
}

// A candidate that starts penetrated is rejected with its name.
#[test]
fn penetrated_start_is_rejected() {
    let sys = masses(vec![1.0], f64::INFINITY);
    let floor = Floor(1);
    let err = ActiveSetStepper::new(
        &sys,
        &floor,
        State::new(0.0, vec![-1e-3], vec![0.0]),
        params(),
    )
    .err()
    .unwrap();
    assert!(err.to_string().contains("mass 0 on the floor"), "{err}");
}
