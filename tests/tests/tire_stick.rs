//! The stick condition of the rolling tire's Coulomb contact holds on the material slip
//! velocity (issue 38 item 5). Reference: Coulomb's law itself (Ribaric §7.3/§8.4.3): a contact
//! node whose friction force lies strictly inside the cone μλ sticks, so the velocity of the
//! tire material at that node relative to the road is zero. In the Eulerian tire that velocity
//! is, Ribaric (7.10),
//!
//! ```text
//!   v = Ω (η × s) + T_c ż + Ω T_c,θ z
//! ```
//!
//! (rigid rotation, deflection rate at the fixed point in space, and the deflection transported
//! through the patch by the rotation). The check recomputes `v` from the state after a step,
//! independently of the contact solve, with the upwind `T_c,θ` the contact uses
//! ([`tire::ReducedTire::tc_theta_upwind`]). Before the transport term was in the contact's
//! tangential rows, "sticking" nodes slid at 1–10 mm/s (branch diagnosis of 2026-12-06).

use tire::*;

use crate::common::{isotropic_reduced_tire, rig};

/// A tire with a patch of several rows of contact nodes: the coarse tire of the validation
/// tests (isotropic tread of 150 MPa, no cords) on 192 × 8 elements, the 39 contact nodes of
/// the ±12° patch (the 96-element tire has three nodes in contact, two of them sliding).
fn tire() -> ReducedTire {
    isotropic_reduced_tire(192, 12.0, 39)
}

/// Free rolling at a slip angle of 0.1° on the flat road (μ = 0.85, 60 km/h), 0.1 s:
/// at every node in contact whose friction force is below 0.999 μλ, the tangential material
/// slip is below 1e-6 m/s (the contact solve's tolerance); there are such nodes.
#[test]
fn sticking_nodes_have_zero_material_slip() {
    let red = &tire();
    let mut rc = rig(GroundKind::Road, false, 0.85);
    rc.wheel.slip_angle_deg = 0.1;
    let mu = rc.rolling.friction;
    let mut start = start_rolling(red, &rc).unwrap();
    let sim = &mut start.sim;
    let h = sim.config().time_step;
    let steps = (0.1 / h).round() as usize;
    for _ in 0..steps {
        sim.step().unwrap();
    }
    let r = sim.reduced();
    let st = &sim.state;
    let nz = st.z.len();
    let dir = usize::from(st.theta_d < 0.0);
    let row = |m: &faer::Mat<f64>, i: usize, x: &[f64]| -> f64 {
        (0..nz).map(|j| m[(i, j)] * x[j]).sum()
    };
    let positions = sim.contact_positions();
    let (mut stick, mut worst) = (0, 0.0f64);
    for (i, s) in r.contact_positions.iter().enumerate() {
        let lam = st.lambda[i];
        let f = st.friction[i];
        let ft = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        if lam <= 0.0 || ft >= 0.999 * mu * lam {
            continue;
        }
        stick += 1;
        let w = st.theta_d;
        let mut v = [w * s[2], 0.0, -w * s[0]];
        for (c, vc) in v.iter_mut().enumerate() {
            *vc +=
                row(&r.tc, 3 * i + c, &st.zd) + w * row(&r.tc_theta_upwind[dir], 3 * i + c, &st.z);
        }
        let g = sim.ground().query(st.t, positions[i]);
        let u: Vec<f64> = (0..3).map(|c| v[c] - g.velocity[c]).collect();
        let un: f64 = (0..3).map(|c| u[c] * g.normal[c]).sum();
        let tangential = (0..3)
            .map(|c| (u[c] - un * g.normal[c]).powi(2))
            .sum::<f64>()
            .sqrt();
        worst = worst.max(tangential);
    }
    println!("{stick} sticking nodes, largest material slip {worst:.3e} m/s");
    assert!(stick >= 3, "only {stick} sticking nodes");
    assert!(worst < 1e-6, "a sticking node slides at {worst:.3e} m/s");
}
