//! A reference multibody model shared by benchmarks and demos: a hanging spherical-joint chain.

use mbd_core::body::BodyState;
use mbd_core::constraints::Spherical;
use mbd_core::forces::Gravity;
use mbd_core::integrators::State;
use mbd_core::marker::Marker;
use mbd_core::{MbdError, MultibodySystem, RigidBody};
use nalgebra::{Vector3, Vector4};

/// A hanging chain of `n` slender links (length `link` \[m\], mass 1 kg each) joined by
/// spherical joints, the first one to the ground at the origin, under gravity −z. Initially
/// straight, tilted by 0.3 rad from the vertical about x, at rest. `(system, initial state)`.
pub fn spherical_chain(n: usize, link: f64) -> Result<(MultibodySystem, State), MbdError> {
    let mut sys = MultibodySystem::new();
    let j = 1.0 * link * link / 12.0;
    let tilt: f64 = 0.3;
    let dir = Vector3::new(0.0, tilt.sin(), -tilt.cos());
    let p = mbd_core::kinematics::euler::from_axis_angle(&Vector3::x(), tilt);
    let mut states = Vec::with_capacity(n);
    for k in 0..n {
        let b = sys.add_body(RigidBody::with_principal(
            &format!("link {k}"),
            1.0,
            [j, j, 1e-3 * j + 1e-9],
        )?);
        let prev = if k == 0 { None } else { Some(b - 1) };
        let pin_prev = if k == 0 {
            Vector3::zeros()
        } else {
            Vector3::new(0.0, 0.0, -0.5 * link)
        };
        sys.add_constraint(Spherical {
            name: format!("joint {k}"),
            i: Marker::point(prev, pin_prev),
            j: Marker::point(Some(b), Vector3::new(0.0, 0.0, 0.5 * link)),
        })?;
        states.push(BodyState::at_rest(dir * (link * (k as f64 + 0.5)), p));
    }
    sys.add_force(Gravity {
        g: Vector3::new(0.0, 0.0, -9.81),
    })?;
    let _ = Vector4::<f64>::zeros();
    let s0 = sys.state(0.0, &states)?;
    Ok((sys, s0))
}
