//! Simulation 3 of Lin §7.2.4 on the Appendix B slab: general rigid-body motion, *emulated*.
//!
//! Lin drives the four bottom corners 16, 18, 28, 30 (12 coordinates, (7.11)) with absolute
//! accelerations recorded every 5 ms in a previous simulation (Fig. 7-12(b)) and linearly
//! interpolated. The tables are not printed (companion seed-002-lin.md §7.2.4, open point 14),
//! so [`record_source`] regenerates them by running that previous simulation:
//!
//! * the unreduced slab (NR, 90×84, nodal-fixed frame 16/28/18 as in the emulation) as a
//!   floating-frame body of `mbd_core::floating`;
//! * a short rigid link (2 m) from node 18 and a long one (3 m) from node 30, spherical joints
//!   at both ends, the far ends on the ground; both links start parallel to the x axis;
//! * the undeformed slab inclined by 45° about the global x axis through nodes 18 and 30 (the
//!   line of the link attachments), its free edge 16–28 swung towards −y and down;
//! * the constant forces {−40, 160, −20} N at node 16 and {60, −240, −30} N at node 28, and
//!   gravity; released from rest.
//!
//! **Assumptions** (the items the companion lists as missing, §16 item 14), each a field of
//! [`Sim3Config`]:
//! * link joints: spherical at both ends (Lin uses spherical joints throughout ch. 5);
//! * link direction: both links point from the slab towards **+x** (ground ends at x = 2 and
//!   x = 7 m). Opposite directions (outwards) would put both ground points and both
//!   attachments on one straight line with the chain fully stretched (a singular, locked
//!   position), which cannot give Lin's "general rigid-body motion";
//! * link mass: 0.5 kg/m, slender rods (the plank links of Lin §5.3.3: 1 kg for 2 m), axial
//!   inertia of a 2 cm radius rod;
//! * inclination: +45° about +x (right-handed), so that the edge 16–28 goes to −y and down;
//! * model that produced the tables: NR with the nodal-fixed frame 16/28/18 (the reference model
//!   of ch. 7), integrated with RK4 at a step that divides the table interval;
//! * duration: `SlabSimConfig::duration_s` (1 s). There is **no floor**: the "hits the bottom"
//!   impact of Lin's run is not modelled, the tables cover the motion without it.
//!
//! The emulation ([`simulate_emulated`]) then runs Lin (7.9) for each basis with the twelve
//! corner coordinates driven by the interpolated tables. Positions and velocities of the drivers
//! are the exact integrals of the piecewise-linear acceleration from the recorded initial state,
//! so the position, velocity and acceleration constraints are mutually consistent.
//!
//! Forces at driven nodes change only the multipliers of the emulation (companion §7.2.4 \[D\]);
//! they are applied anyway, as Lin does.

use super::slab::{LinSlab, SlabMethod, node_position};
use super::slab_sim::{SlabSimConfig, run_observed, slab_system};
use mbd_core::constraints::{DriverLaw, PointDriver, Spherical};
use mbd_core::floating::{FlexState, FloatingSystem, NodeLoad};
use mbd_core::integrators::{Rk4, Stabilization, State, accelerations};
use mbd_core::kinematics::euler::{a_matrix, from_axis_angle};
use mbd_core::marker::Marker;
use mbd_core::{BodyState, RigidBody};
use nalgebra::{Vector3, Vector4};
use reduction::error::{ReductionError, Result};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The driven corner nodes of Lin (7.11), 1-based.
pub const DRIVEN_NODES: [usize; 4] = [16, 18, 28, 30];

/// Direction of both links from the slab towards their ground points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum LinkDirection {
    /// Along +x (default).
    PlusX,
    /// Along −x.
    MinusX,
}

impl LinkDirection {
    fn sign(self) -> f64 {
        match self {
            LinkDirection::PlusX => 1.0,
            LinkDirection::MinusX => -1.0,
        }
    }
}

/// Parameters of the previous simulation of Lin Fig. 7-12(b) that produces the tables.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Sim3Config {
    /// Length of the link at node 18 \[m\] (Lin: 2).
    pub short_link_m: f64,
    /// Length of the link at node 30 \[m\] (Lin: 3).
    pub long_link_m: f64,
    /// Link mass per length \[kg/m\] (not given; 0.5 as the plank links of Lin §5.3.3).
    pub link_mass_per_length_kg_m: f64,
    /// Link radius for the axial inertia `m r²/2` \[m\] (not given; slender rods).
    pub link_radius_m: f64,
    /// Direction of both links from the slab to the ground (not given).
    pub link_direction: LinkDirection,
    /// Inclination of the undeformed slab about global +x through nodes 18 and 30 \[deg\]
    /// (Lin: 45° "towards the −y direction").
    pub inclination_deg: f64,
    /// Constant global force at node 16 \[N\] (Lin: {−40, 160, −20}).
    pub force_node16_n: [f64; 3],
    /// Constant global force at node 28 \[N\] (Lin: {60, −240, −30}).
    pub force_node28_n: [f64; 3],
    /// Sampling interval of the acceleration tables \[s\] (Lin: 5 ms).
    pub table_interval_s: f64,
}

impl Default for Sim3Config {
    fn default() -> Self {
        Self {
            short_link_m: 2.0,
            long_link_m: 3.0,
            link_mass_per_length_kg_m: 0.5,
            link_radius_m: 0.02,
            link_direction: LinkDirection::PlusX,
            inclination_deg: 45.0,
            force_node16_n: [-40.0, 160.0, -20.0],
            force_node28_n: [60.0, -240.0, -30.0],
            table_interval_s: 5e-3,
        }
    }
}

/// Absolute accelerations of the driven nodes sampled at `t_k = k·interval` (Lin Fig. 7-12(b)
/// lookup tables), linearly interpolated in time, with the initial positions and velocities.
#[derive(Debug, Clone, PartialEq)]
pub struct AccelTable {
    /// Sampling interval \[s\].
    pub interval_s: f64,
    /// Driven nodes (1-based Lin numbers).
    pub nodes: Vec<usize>,
    /// Initial global positions of the nodes \[m\].
    pub x0: Vec<Vector3<f64>>,
    /// Initial global velocities of the nodes \[m/s\].
    pub v0: Vec<Vector3<f64>>,
    /// `acc[k][i]`: global acceleration of node `nodes[i]` at `t_k` \[m/s²\].
    pub acc: Vec<Vec<Vector3<f64>>>,
    // exact integrals of the interpolant at the samples
    vel: Vec<Vec<Vector3<f64>>>,
    pos: Vec<Vec<Vector3<f64>>>,
}

impl AccelTable {
    /// Builds the table; velocities and positions at the samples are the exact integrals of the
    /// piecewise-linear acceleration.
    pub fn new(
        interval_s: f64, nodes: Vec<usize>, x0: Vec<Vector3<f64>>, v0: Vec<Vector3<f64>>,
        acc: Vec<Vec<Vector3<f64>>>,
    ) -> Result<Self> {
        let bad = |reason: String| ReductionError::InvalidParameter {
            name: "acceleration table".into(),
            reason,
        };
        if !(interval_s.is_finite() && interval_s > 0.0) {
            return Err(bad(format!("interval {interval_s} s is not positive")));
        }
        if acc.is_empty() {
            return Err(bad("no samples".into()));
        }
        let n = nodes.len();
        if x0.len() != n || v0.len() != n {
            return Err(bad(format!(
                "{} initial positions and {} velocities for {n} nodes",
                x0.len(),
                v0.len()
            )));
        }
        if let Some(k) = acc.iter().position(|row| row.len() != n) {
            return Err(bad(format!(
                "sample {k} has {} nodes, expected {n}",
                acc[k].len()
            )));
        }
        let h = interval_s;
        let mut vel = vec![v0.clone()];
        let mut pos = vec![x0.clone()];
        for k in 1..acc.len() {
            let (vp, xp) = (&vel[k - 1], &pos[k - 1]);
            let v: Vec<Vector3<f64>> = (0..n)
                .map(|i| vp[i] + 0.5 * h * (acc[k - 1][i] + acc[k][i]))
                .collect();
            let x: Vec<Vector3<f64>> = (0..n)
                .map(|i| xp[i] + h * vp[i] + h * h * (acc[k - 1][i] / 3.0 + acc[k][i] / 6.0))
                .collect();
            vel.push(v);
            pos.push(x);
        }
        Ok(Self {
            interval_s,
            nodes,
            x0,
            v0,
            acc,
            vel,
            pos,
        })
    }

    /// Time of the last sample \[s\]; beyond it the last acceleration is held.
    pub fn end_time(&self) -> f64 {
        (self.acc.len() - 1) as f64 * self.interval_s
    }

    /// Position \[m\], velocity \[m/s\] and acceleration \[m/s²\] of node index `i` at `t` \[s\]: the
    /// linear interpolant of the samples and its exact integrals.
    pub fn motion(&self, i: usize, t: f64) -> [Vector3<f64>; 3] {
        let h = self.interval_s;
        let last = self.acc.len() - 1;
        let k = ((t / h).floor().max(0.0) as usize).min(last);
        let tau = (t - k as f64 * h).max(0.0);
        let a0 = self.acc[k][i];
        let da = if k < last {
            (self.acc[k + 1][i] - a0) / h
        } else {
            Vector3::zeros()
        };
        let (v0, x0) = (self.vel[k][i], self.pos[k][i]);
        [
            x0 + v0 * tau + a0 * (tau * tau / 2.0) + da * (tau * tau * tau / 6.0),
            v0 + a0 * tau + da * (tau * tau / 2.0),
            a0 + da * tau,
        ]
    }
}

/// The recorded tables and the previous simulation's own node-8 history.
#[derive(Debug, Clone)]
pub struct SourceRun {
    /// The acceleration tables of nodes 16, 18, 28, 30.
    pub table: AccelTable,
    /// Times of the source steps \[s\].
    pub t: Vec<f64>,
    /// Local deflection δ'8 of the source (NR, frame 16/28/18) at those times \[m\].
    pub node8: Vec<[f64; 3]>,
    /// Largest position-level constraint residual of the source \[m\].
    pub max_drift_m: f64,
}

/// The undeformed slab at rest (`nz` modal coordinates) with its frame at `r0` \[m\] and
/// Euler parameters `e0`: the initial state of the source and emulation systems.
fn slab_at_rest(r0: Vector3<f64>, e0: Vector4<f64>, nz: usize) -> FlexState {
    FlexState {
        r: r0,
        p: e0,
        rdot: Vector3::zeros(),
        omega_local: Vector3::zeros(),
        z: vec![0.0; nz],
        zdot: vec![0.0; nz],
    }
}

/// Initial frame of the slab: origin (node 16) and Euler parameters, from the inclination
/// about the x axis through nodes 18 and 30.
fn initial_frame(p: &Sim3Config) -> (Vector3<f64>, Vector4<f64>) {
    let e = from_axis_angle(&Vector3::x(), p.inclination_deg.to_radians());
    let a = a_matrix(&e);
    let s18 = Vector3::from(node_position(18));
    // global = s18 + A (s − s18); node 16 is s = 0
    (s18 - a * s18, e)
}

fn check(p: &SlabSimConfig) -> Result<()> {
    super::slab_sim::validated(p)?;
    let s = &p.sim3;
    let bad = |name: &str, reason: String| {
        Err(ReductionError::InvalidParameter {
            name: format!("sim3.{name}"),
            reason,
        })
    };
    for (name, v) in [
        ("short_link_m", s.short_link_m),
        ("long_link_m", s.long_link_m),
        ("link_mass_per_length_kg_m", s.link_mass_per_length_kg_m),
        ("link_radius_m", s.link_radius_m),
        ("table_interval_s", s.table_interval_s),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return bad(name, format!("must be positive, got {v}"));
        }
    }
    if !s.inclination_deg.is_finite() {
        return bad("inclination_deg", "is not finite".into());
    }
    for (name, f) in [
        ("force_node16_n", s.force_node16_n),
        ("force_node28_n", s.force_node28_n),
    ] {
        if !f.iter().all(|x| x.is_finite()) {
            return bad(name, "has a non-finite component".into());
        }
    }
    if !(p.step_s.is_finite() && p.step_s > 0.0) {
        return Err(ReductionError::InvalidParameter {
            name: "step_s".into(),
            reason: format!("must be positive, got {}", p.step_s),
        });
    }
    Ok(())
}

fn mbd_err(what: &str) -> impl Fn(mbd_core::MbdError) -> ReductionError + '_ {
    move |e| ReductionError::Numerical {
        what: what.to_string(),
        detail: e.to_string(),
    }
}

fn add_forces(sys: &mut FloatingSystem, fb: usize, p: &Sim3Config) -> Result<()> {
    for (j, f) in [(16usize, p.force_node16_n), (28, p.force_node28_n)] {
        let f = Vector3::from(f);
        sys.add_load(NodeLoad {
            name: format!("constant force at node {j}"),
            point: Marker::node(fb, j - 1),
            force: Box::new(move |_| f),
        })
        .map_err(mbd_err("simulation-3 loads"))?;
    }
    Ok(())
}

/// The previous simulation of Lin Fig. 7-12(b) (see the module docs for every assumption):
/// the NR slab on two rigid links, and its initial state at rest.
pub fn source_system(slab: &LinSlab, p: &SlabSimConfig) -> Result<(FloatingSystem, State)> {
    check(p)?;
    let s3 = &p.sim3;
    let err = mbd_err("simulation-3 source system");
    // the rigid links are added below; rigid and flexible bodies are numbered separately
    let (mut sys, fb, nz) = slab_system(slab, SlabMethod::NoReduction, p.n_modes, &err)?;
    let (r0, e0) = initial_frame(s3);
    let a0 = a_matrix(&e0);
    let mut rigid = Vec::new();
    let dir = s3.link_direction.sign();
    let mut links = Vec::new();
    for (j, len) in [(18usize, s3.short_link_m), (30, s3.long_link_m)] {
        let m = s3.link_mass_per_length_kg_m * len;
        let jt = m * len * len / 12.0;
        let ja = 0.5 * m * s3.link_radius_m * s3.link_radius_m;
        let link = RigidBody::with_principal(&format!("link at node {j}"), m, [ja, jt, jt])
            .map_err(&err)?;
        let k = sys.add_rigid(link);
        let attach = r0 + a0 * Vector3::from(node_position(j));
        let centre = attach + Vector3::new(dir * len / 2.0, 0.0, 0.0);
        rigid.push(BodyState::at_rest(centre, Vector4::new(1.0, 0.0, 0.0, 0.0)));
        links.push((k, j, len, attach));
    }
    for (k, j, len, attach) in links {
        let half = Vector3::new(dir * len / 2.0, 0.0, 0.0);
        sys.add_constraint(Spherical {
            name: format!("link {j} to ground"),
            i: Marker::point(Some(k), half),
            j: Marker::point(None, attach + 2.0 * half),
        })
        .map_err(&err)?;
        sys.add_constraint(Spherical {
            name: format!("link {j} to node {j}"),
            i: Marker::point(Some(k), -half),
            j: Marker::node(fb, j - 1),
        })
        .map_err(&err)?;
    }
    add_forces(&mut sys, fb, s3)?;
    let st = sys
        .state(0.0, &rigid, &[slab_at_rest(r0, e0, nz)])
        .map_err(&err)?;
    Ok((sys, st))
}

/// Runs the previous simulation and records the acceleration tables of nodes 16, 18, 28, 30
/// every `sim3.table_interval_s` up to `duration_s` (plus one sample to cover the end). The
/// RK4 step is the largest divisor of the interval not above `step_s`.
pub fn record_source(slab: &LinSlab, p: &SlabSimConfig) -> Result<SourceRun> {
    let (sys, st) = source_system(slab, p)?;
    let fb = 0; // the only flexible body
    let interval = p.sim3.table_interval_s;
    let per = (interval / p.step_s - 1e-9).ceil().max(1.0) as usize;
    let h = interval / per as f64;
    let n_samples = (p.duration_s / interval - 1e-9).ceil() as usize + 1;
    let t_end = (n_samples - 1) as f64 * interval;
    let points: Vec<Marker> = DRIVEN_NODES
        .iter()
        .map(|&j| Marker::node(fb, j - 1))
        .collect();
    let x0: Vec<Vector3<f64>> = points.iter().map(|q| sys.point_position(&st, q)).collect();
    let v0: Vec<Vector3<f64>> = points.iter().map(|q| sys.point_velocity(&st, q)).collect();
    let mut acc = Vec::with_capacity(n_samples);
    let mut t = Vec::new();
    let mut node8 = Vec::new();
    let mut drift = 0.0f64;
    let mut phi = vec![0.0; mbd_core::SecondOrderSystem::n_c(&sys)];
    let mut failure: Option<String> = None;
    let mut step = 0usize;
    let stab = Stabilization::default();
    Rk4::new(h)
        .integrate(&sys, st, t_end, |x| {
            let d = sys.node_deflection(x, fb, 7);
            t.push(x.t);
            node8.push([d.x, d.y, d.z]);
            if mbd_core::SecondOrderSystem::constraint_residual(&sys, x.t, &x.q, &mut phi).is_ok() {
                drift = drift.max(phi.iter().fold(0.0, |a: f64, b| a.max(b.abs())));
            }
            if step.is_multiple_of(per) && failure.is_none() {
                match accelerations(&sys, x, &stab) {
                    Ok(a) => acc.push(
                        points
                            .iter()
                            .map(|q| sys.point_acceleration(x, &a.vdot, q))
                            .collect(),
                    ),
                    Err(e) => failure = Some(format!("t = {} s: {e}", x.t)),
                }
            }
            step += 1;
        })
        .map_err(mbd_err("simulation-3 source run"))?;
    if let Some(f) = failure {
        return Err(ReductionError::Numerical {
            what: "simulation-3 source accelerations".into(),
            detail: f,
        });
    }
    let table = AccelTable::new(interval, DRIVEN_NODES.to_vec(), x0, v0, acc)?;
    Ok(SourceRun {
        table,
        t,
        node8,
        max_drift_m: drift,
    })
}

/// The emulation of Lin (7.9)/(7.11) for `method`: the twelve corner coordinates driven by the
/// interpolated tables, gravity and the two constant forces, starting from the source's initial
/// configuration at rest.
pub fn emulation_system(
    slab: &LinSlab, method: SlabMethod, table: &Arc<AccelTable>, p: &SlabSimConfig,
) -> Result<(FloatingSystem, State)> {
    check(p)?;
    if table.nodes != DRIVEN_NODES {
        return Err(ReductionError::InvalidParameter {
            name: "acceleration table".into(),
            reason: format!("drives nodes {:?}, expected {DRIVEN_NODES:?}", table.nodes),
        });
    }
    let what = format!("simulation-3 emulation ({})", method.label());
    let err = mbd_err(&what);
    let (mut sys, fb, nz) = slab_system(slab, method, p.n_modes, &err)?;
    for (i, &j) in DRIVEN_NODES.iter().enumerate() {
        for c in 0..3 {
            let tab = Arc::clone(table);
            sys.add_constraint(PointDriver {
                name: format!("node {j} {}", ["x", "y", "z"][c]),
                point: Marker::node(fb, j - 1),
                component: c,
                law: DriverLaw::Custom(Arc::new(move |t| {
                    let [x, v, a] = tab.motion(i, t);
                    (x[c], v[c], a[c])
                })),
            })
            .map_err(&err)?;
        }
    }
    add_forces(&mut sys, fb, &p.sim3)?;
    let (r0, e0) = initial_frame(&p.sim3);
    let st = sys
        .state(0.0, &[], &[slab_at_rest(r0, e0, nz)])
        .map_err(&err)?;
    Ok((sys, st))
}

/// Runs the emulation for `method`; `observer(t, δ'_8)` receives the local deflection of node 8
/// \[m\] at the start and after every RK4 step of `step_s`. Returns the largest position-level
/// constraint residual \[m\].
pub fn simulate_emulated<R: mbd_core::integrators::Proceed>(
    slab: &LinSlab, method: SlabMethod, table: &Arc<AccelTable>, p: &SlabSimConfig,
    observer: impl FnMut(f64, [f64; 3]) -> R,
) -> Result<f64> {
    super::slab_sim::validated(p)?;
    let (sys, st) = emulation_system(slab, method, table, p)?;
    let what = format!("simulation-3 emulation ({})", method.label());
    // the step divides the table interval so that the kinks of the interpolant fall on steps
    let interval = p.sim3.table_interval_s;
    let per = (interval / p.step_s - 1e-9).ceil().max(1.0);
    run_observed(&sys, st, interval / per, p.duration_s, observer, what)
}
