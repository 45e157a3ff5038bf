//! Time simulations 1 and 2 of Lin §7.2 on the Appendix B slab: the nodal-fixed modal
//! formulation with prescribed absolute accelerations of boundary coordinates (Lin (7.7)–(7.9)),
//! built on mbd-core's floating-frame bodies and integrated with mbd-core's RK4.

use super::slab::{G, LinSlab, SlabMethod, slab_basis};
use crate::error::{ReductionError, Result};
use mbd_core::floating::{
    AxisCondition, FlexBody, FlexState, FloatingSystem, Point, PrescribedMotion,
};
use mbd_core::integrators::{Rk4, State};
use nalgebra::{Vector3, Vector4};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Which simulation of Lin §7.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SlabSimulation {
    /// Simulation 1 (§7.2.2): node 16 fixed, 18 in x, 28 and 30 in z; gravity; from rest.
    NoRigidMotion,
    /// Simulation 2 (§7.2.3): nodes 16 and 18 fixed, node 30 orbiting with the prescribed
    /// acceleration (7.10), initial angular velocity −Ω about y.
    Orbit,
}

/// Parameters of a slab simulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SlabSimParams {
    /// End time [s] (not given by Lin; companion §13.2).
    pub duration_s: f64,
    /// RK4 step [s] (highest slab frequency ≈ 73 Hz: 1 ms is well inside stability).
    pub step_s: f64,
    /// Fixed-interface modes kept by MT, CB, MC (Lin: 6).
    pub n_modes: usize,
    /// Orbit radius R of simulation 2 [m] (Lin (7.10): 4).
    pub orbit_radius_m: f64,
    /// Orbit period T of simulation 2 [s] (Lin: 1).
    pub orbit_period_s: f64,
}

impl Default for SlabSimParams {
    fn default() -> Self {
        Self {
            duration_s: 1.0,
            step_s: 1e-3,
            n_modes: 6,
            orbit_radius_m: 4.0,
            orbit_period_s: 1.0,
        }
    }
}

/// Builds the floating-frame system and its initial state for `method` and `sim`.
pub fn build(
    slab: &LinSlab,
    method: SlabMethod,
    sim: SlabSimulation,
    p: &SlabSimParams,
) -> Result<(FloatingSystem, State)> {
    let basis = slab_basis(slab, method, p.n_modes)?;
    let mbd = |e: mbd_core::MbdError| ReductionError::Numerical {
        what: format!("slab system ({})", method.label()),
        detail: e.to_string(),
    };
    let body = FlexBody::new(
        "slab",
        &slab.s,
        slab.m.as_ref(),
        slab.k.as_ref(),
        basis.psi.as_ref(),
        AxisCondition::NodalFixed,
    )
    .map_err(mbd)?;
    let mut sys = FloatingSystem::new();
    sys.gravity = Vector3::new(0.0, 0.0, -G);
    let fb = sys.add_flex(body);
    let node = |j: usize| Point::FlexNode {
        body: fb,
        node: j - 1,
    };
    let fixed = |sys: &mut FloatingSystem, j: usize, c: usize| -> Result<()> {
        let x0 = super::slab::node_position(j)[c];
        sys.add_driver(PrescribedMotion {
            name: format!("node {j} {}", ["x", "y", "z"][c]),
            point: node(j),
            component: c,
            motion: Box::new(move |_| [x0, 0.0, 0.0]),
        })
        .map_err(mbd)
    };
    let mut omega0 = Vector3::zeros();
    match sim {
        SlabSimulation::NoRigidMotion => {
            for c in 0..3 {
                fixed(&mut sys, 16, c)?;
            }
            fixed(&mut sys, 18, 0)?;
            fixed(&mut sys, 28, 2)?;
            fixed(&mut sys, 30, 2)?;
        }
        SlabSimulation::Orbit => {
            for c in 0..3 {
                fixed(&mut sys, 16, c)?;
                fixed(&mut sys, 18, c)?;
            }
            let r = p.orbit_radius_m;
            let w = 2.0 * PI / p.orbit_period_s;
            let a = r * w * w;
            // (7.10) and its integrals with x(0) = R, ẋ(0) = 0, z(0) = 0, ż(0) = RΩ
            // (companion §7.2.3: the second harmonic adds a secular drift −RΩ/16 in z).
            let xs: Box<dyn Fn(f64) -> [f64; 3] + Send + Sync> = Box::new(move |t| {
                [
                    r * (w * t).cos() + r / 16.0 * ((2.0 * w * t).cos() - 1.0),
                    -r * w * (w * t).sin() - r * w / 8.0 * (2.0 * w * t).sin(),
                    -a * ((w * t).cos() + 0.25 * (2.0 * w * t).cos()),
                ]
            });
            let zs: Box<dyn Fn(f64) -> [f64; 3] + Send + Sync> = Box::new(move |t| {
                [
                    r * (w * t).sin() + r / 32.0 * (2.0 * w * t).sin() - r * w / 16.0 * t,
                    r * w * (w * t).cos() + r * w / 16.0 * (2.0 * w * t).cos() - r * w / 16.0,
                    -a * ((w * t).sin() + 0.125 * (2.0 * w * t).sin()),
                ]
            });
            let y30 = super::slab::node_position(30)[1];
            for (c, motion) in [
                (0usize, xs),
                (
                    1,
                    Box::new(move |_| [y30, 0.0, 0.0])
                        as Box<dyn Fn(f64) -> [f64; 3] + Send + Sync>,
                ),
                (2, zs),
            ] {
                sys.add_driver(PrescribedMotion {
                    name: format!("node 30 {}", ["x", "y", "z"][c]),
                    point: node(30),
                    component: c,
                    motion,
                })
                .map_err(mbd)?;
            }
            omega0 = Vector3::new(0.0, -w, 0.0);
        }
    }
    let nz = basis.psi.ncols();
    let st = sys
        .state(
            0.0,
            &[],
            &[FlexState {
                r: Vector3::zeros(),
                p: Vector4::new(1.0, 0.0, 0.0, 0.0),
                rdot: Vector3::zeros(),
                omega_local: omega0,
                z: vec![0.0; nz],
                zdot: vec![0.0; nz],
            }],
        )
        .map_err(mbd)?;
    Ok((sys, st))
}

/// Runs one simulation; `observer(t, δ'_8)` receives the local deflection of node 8 [m] at the
/// start and after every step. Returns the largest position-level constraint residual [m].
pub fn simulate(
    slab: &LinSlab,
    method: SlabMethod,
    sim: SlabSimulation,
    p: &SlabSimParams,
    mut observer: impl FnMut(f64, [f64; 3]),
) -> Result<f64> {
    let (sys, st) = build(slab, method, sim, p)?;
    let mut drift = 0.0f64;
    let mut phi = vec![0.0; mbd_core::SecondOrderSystem::n_c(&sys)];
    let mut err = None;
    Rk4::new(p.step_s)
        .integrate(&sys, st, p.duration_s, |x| {
            let d = sys.node_deflection(x, 0, 7);
            observer(x.t, [d.x, d.y, d.z]);
            if mbd_core::SecondOrderSystem::constraint_residual(&sys, x.t, &x.q, &mut phi).is_ok() {
                drift = drift.max(phi.iter().fold(0.0, |a: f64, b| a.max(b.abs())));
            } else {
                err = Some(x.t);
            }
        })
        .map_err(|e| ReductionError::Numerical {
            what: format!("slab simulation ({})", method.label()),
            detail: e.to_string(),
        })?;
    if let Some(t) = err {
        return Err(ReductionError::Numerical {
            what: format!("slab simulation ({})", method.label()),
            detail: format!("constraint evaluation failed at t = {t} s"),
        });
    }
    Ok(drift)
}
