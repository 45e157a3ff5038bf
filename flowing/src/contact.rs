//! The string partly wrapped on two pulleys with a variable-size contact area
//! (Ribaric (4.10), (4.11)) and the travelling string with variable contact (4.31)–(4.40).
//!
//! All candidate contact nodes (the `c` set: the largest set of nodes that can ever touch a
//! pulley) are kept; only the active ones are constrained to the pulley surface, `u_i = s(x_i)`,
//! by Lagrange multipliers ("we only need to adjust the entries of the Jacobian").
//!
//! Coordinates `y` with nodal deflections `u = T y`: `T = I` gives the nodal form (4.10);
//! `T = [Ψ^f Ψ_s^c; 0 Ψ^c]` the Craig–Bampton / flowing-material form (4.11), (4.32)–(4.35).
//! With the material flowing at `ẋ` through the fixed mesh the material acceleration is
//! `ü = Tÿ + ẍ T_,s y + ẋ² T_,ss y + 2ẋ T_,s ẏ` ((4.36)–(4.39); `T_,s` taken on the full nodal field of
//! every column in spatial node order, notes §1.4.5) and the equations are
//!
//! ```text
//!   TᵀMT ÿ + 2ẋ TᵀMT_,s ẏ + (ẍ TᵀMT_,s + ẋ² TᵀMT_,ss + TᵀKT) y + D_Aᵀλ = Tᵀ f(t)
//!   D_A y = s_A          (active c-nodes on the pulley surface)
//! ```
//!
//! **Choice (documented):** Ribaric (4.40) keeps the c-rows un-projected and the f-rows
//! projected with `Ψ^fT` (a Petrov–Galerkin form with a non-symmetric coefficient matrix); here all
//! rows are projected with `Tᵀ` (Galerkin). The two are identical when all f-modes are kept
//! (tested against the nodal model) and the Galerkin form has a symmetric positive mass matrix,
//! conserves energy, and fits [`SecondOrderSystem`]. The constraint is written on the Eulerian
//! deflection at the fixed mesh node (`∂u/∂t = 0` there), which is (4.40)'s third row with
//! `γ = ẍ D b^c + D c^c`.
//!
//! Contact law (notes U4): an inactive candidate becomes active when its gap
//! `g_i = u_i − s(x_i)` crosses below `−gap_tol` (located by mbd-core's Dormand–Prince event
//! location); the impact is perfectly plastic (mass-weighted velocity projection onto
//! `D_A ẏ = 0`, mbd-core `project_velocities`); an active node is released when its contact
//! force `p_i = −λ_i` (compressive positive) crosses below `−force_tol`.

use crate::derivative::{DerivativeMethod, mode_shape_derivatives};
use crate::error::{FlowError, invalid};
use crate::pulley::PulleyObstacle;
use crate::string_fe::StringMesh;
use crate::travelling::AxialMotion;
use faer::linalg::solvers::Solve;
use faer::{Mat, MatRef};
use fe_model::dense_modes;
use mbd_core::Workspace;
use mbd_core::integrators::{
    DormandPrince, Event, EventAction, Stabilization, State, accelerations, project_positions,
    project_velocities,
};
use mbd_core::{MbdError, SecondOrderSystem, SysMatrix};

/// A candidate contact node.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// Mesh node (DOF) index.
    pub node: usize,
    /// Pulley index.
    pub pulley: usize,
    /// Axial position \[m\].
    pub x: f64,
    /// Pulley surface height under the node \[m\].
    pub surface: f64,
}

/// Transverse load `f(t) = amplitude · sin(2π·frequency·t)` at the node nearest to `x`.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields)]
pub struct HarmonicLoad {
    /// Axial position of the loaded node \[m\].
    pub x: f64,
    /// Force amplitude \[N\] (positive: away from the pulleys).
    pub amplitude: f64,
    /// Frequency \[Hz\].
    pub frequency: f64,
}

/// The wrapped string (4.10)/(4.11)/(4.40) with a given active set.
#[derive(Debug, Clone)]
pub struct ContactString {
    /// Transformation `u = T y` (`n × r`).
    pub t: Mat<f64>,
    /// `TᵀMT`.
    pub m_r: Mat<f64>,
    /// `TᵀKT`.
    pub k_r: Mat<f64>,
    /// `TᵀMT_,s`.
    pub mx_r: Mat<f64>,
    /// `TᵀMT_,ss`.
    pub mxx_r: Mat<f64>,
    /// Candidate contact nodes.
    pub candidates: Vec<Candidate>,
    /// Active flags (one per candidate).
    pub active: Vec<bool>,
    /// Axial motion (prescribed only).
    pub motion: AxialMotion,
    /// Optional harmonic load, as a nodal index and the load.
    pub load: Option<(usize, HarmonicLoad)>,
    /// Names of the coordinates (for diagnostics).
    pub coordinate_kind: &'static str,
}

/// Candidate nodes: the mesh nodes within `half_width` of a pulley centre \[m\].
pub fn candidates(
    mesh: &StringMesh, pulleys: &[PulleyObstacle], half_width: f64,
) -> Result<Vec<Candidate>, FlowError> {
    let mut c = Vec::new();
    for (p, pl) in pulleys.iter().enumerate() {
        pl.validate(&format!("pulley {p}"))?;
        if !(half_width > 0.0 && half_width < pl.radius) {
            return Err(invalid(
                "contact: candidate half width",
                format!(
                    "{half_width} must be positive and below the radius {} of pulley {p}",
                    pl.radius
                ),
            ));
        }
        for (j, &x) in mesh.grid.positions().iter().enumerate() {
            if (x - pl.center_x).abs() <= half_width {
                let surface = pl
                    .surface(x)
                    .ok_or_else(|| invalid("contact", "node outside pulley"))?;
                if c.iter().any(|k: &Candidate| k.node == j) {
                    return Err(invalid(
                        format!("contact: node {j}"),
                        "lies over two pulleys",
                    ));
                }
                c.push(Candidate {
                    node: j,
                    pulley: p,
                    x,
                    surface,
                });
            }
        }
    }
    if c.is_empty() {
        return Err(invalid("contact", "no mesh node lies over a pulley"));
    }
    Ok(c)
}

fn motion_prescribed(motion: AxialMotion) -> Result<AxialMotion, FlowError> {
    if motion.prescribed(0.0).is_none() {
        return Err(invalid(
            "contact string: axial motion",
            "must be prescribed (constant, ramp or harmonic)",
        ));
    }
    Ok(motion)
}

impl ContactString {
    fn build(
        mesh: &StringMesh, t: Mat<f64>, candidates: Vec<Candidate>, method: DerivativeMethod,
        motion: AxialMotion, load: Option<HarmonicLoad>, coordinate_kind: &'static str,
    ) -> Result<Self, FlowError> {
        let motion = motion_prescribed(motion)?;
        let d = mode_shape_derivatives(&[mesh.flow_line()], method, t.as_ref())?;
        let mt = &mesh.mass * &t;
        let m_r = t.transpose() * &mt;
        let k_r = t.transpose() * (&mesh.stiffness * &t);
        let mx_r = mt.transpose() * &d.d1;
        let mxx_r = mt.transpose() * &d.d2;
        let load = match load {
            None => None,
            Some(l) => {
                let p = mesh.grid.positions();
                let j = (0..p.len())
                    .min_by(|&a, &b| (p[a] - l.x).abs().total_cmp(&(p[b] - l.x).abs()))
                    .ok_or_else(|| invalid("load", "empty mesh"))?;
                Some((j, l))
            }
        };
        let active = vec![false; candidates.len()];
        Ok(Self {
            t,
            m_r,
            k_r,
            mx_r,
            mxx_r,
            candidates,
            active,
            motion,
            load,
            coordinate_kind,
        })
    }

    /// Nodal form (4.10): `y = u`.
    pub fn nodal(
        mesh: &StringMesh, candidates: Vec<Candidate>, method: DerivativeMethod,
        motion: AxialMotion, load: Option<HarmonicLoad>,
    ) -> Result<Self, FlowError> {
        let n = mesh.n_dofs();
        Self::build(
            mesh,
            Mat::identity(n, n),
            candidates,
            method,
            motion,
            load,
            "nodal deflection",
        )
    }

    /// Craig–Bampton / flowing-material form (4.11), (4.34): `k_f` fixed-interface normal modes
    /// `Ψ^f` of the free nodes (truncated), static modes `Ψ_s = −K^ff⁻¹K^fc` and all normal modes
    /// `Ψ^c` of the candidate nodes, `Ψ_s^c = Ψ_s Ψ^c` (4.35). Eigen problems by fe-model.
    pub fn craig_bampton(
        mesh: &StringMesh, candidates: Vec<Candidate>, k_f: usize, method: DerivativeMethod,
        motion: AxialMotion, load: Option<HarmonicLoad>,
    ) -> Result<Self, FlowError> {
        let n = mesh.n_dofs();
        let mut is_c = vec![false; n];
        for c in &candidates {
            is_c[c.node] = true;
        }
        let cset: Vec<usize> = (0..n).filter(|&i| is_c[i]).collect();
        let fset: Vec<usize> = (0..n).filter(|&i| !is_c[i]).collect();
        if k_f == 0 || k_f > fset.len() {
            return Err(invalid(
                "contact string: free modes",
                format!("asked for {k_f} modes of {} free nodes", fset.len()),
            ));
        }
        let sub = |a: &Mat<f64>, r: &[usize], c: &[usize]| {
            Mat::from_fn(r.len(), c.len(), |i, j| a[(r[i], c[j])])
        };
        let kff = sub(&mesh.stiffness, &fset, &fset);
        let mff = sub(&mesh.mass, &fset, &fset);
        let kfc = sub(&mesh.stiffness, &fset, &cset);
        let kcc = sub(&mesh.stiffness, &cset, &cset);
        let mcc = sub(&mesh.mass, &cset, &cset);
        let psi_f = dense_modes(kff.as_ref(), mff.as_ref(), k_f)?.vectors;
        let psi_c = dense_modes(kcc.as_ref(), mcc.as_ref(), cset.len())?.vectors;
        let llt = kff
            .llt(faer::Side::Lower)
            .map_err(|e| FlowError::LinearAlgebra {
                what: "K^ff (static modes)".into(),
                reason: format!("{e:?}"),
            })?;
        let psi_s = -llt.solve(&kfc);
        let psi_sc = &psi_s * &psi_c;
        let nc = cset.len();
        let mut t = Mat::<f64>::zeros(n, k_f + nc);
        for (i, &r) in fset.iter().enumerate() {
            for j in 0..k_f {
                t[(r, j)] = psi_f[(i, j)];
            }
            for j in 0..nc {
                t[(r, k_f + j)] = psi_sc[(i, j)];
            }
        }
        for (i, &r) in cset.iter().enumerate() {
            for j in 0..nc {
                t[(r, k_f + j)] = psi_c[(i, j)];
            }
        }
        Self::build(
            mesh,
            t,
            candidates,
            method,
            motion,
            load,
            "Craig-Bampton modal coordinate",
        )
    }

    /// Number of generalized coordinates `r`.
    pub fn dim(&self) -> usize {
        self.t.ncols()
    }

    /// Nodal deflections `u = T y` \[m\].
    pub fn deflection(&self, y: &[f64]) -> Vec<f64> {
        (0..self.t.nrows())
            .map(|i| (0..y.len()).map(|j| self.t[(i, j)] * y[j]).sum())
            .collect()
    }

    /// Gap of candidate `c`: `u_i − s(x_i)` \[m\].
    pub fn gap(&self, c: usize, y: &[f64]) -> f64 {
        let k = &self.candidates[c];
        (0..y.len())
            .map(|j| self.t[(k.node, j)] * y[j])
            .sum::<f64>()
            - k.surface
    }

    fn active_list(&self) -> Vec<usize> {
        (0..self.candidates.len())
            .filter(|&c| self.active[c])
            .collect()
    }

    /// Contact forces `p = −λ` \[N\] (compressive positive) of the active candidates, in the order
    /// of the candidate list (`0` for inactive ones), from the index-1 equations.
    pub fn contact_forces(&self, state: &State) -> Result<Vec<f64>, FlowError> {
        let acc = accelerations(self, state, &Stabilization::default())?;
        let mut p = vec![0.0; self.candidates.len()];
        for (row, c) in self.active_list().into_iter().enumerate() {
            p[c] = -acc.lambda[row];
        }
        Ok(p)
    }

    /// Effective stiffness at speed `ẋ` and acceleration `ẍ`: `TᵀKT + ẍ TᵀMT_,s + ẋ² TᵀMT_,ss`.
    fn k_eff(&self, s: f64, a: f64) -> Mat<f64> {
        let r = self.dim();
        Mat::from_fn(r, r, |i, j| {
            self.k_r[(i, j)] + a * self.mx_r[(i, j)] + s * s * self.mxx_r[(i, j)]
        })
    }

    /// Energy `½ẏᵀTᵀMTẏ + ½yᵀ(TᵀKT + ẋ²TᵀMT_,ss)y` \[J\] at speed `ẋ` (conserved for constant speed,
    /// no load, FE-consistent derivatives, and no impacts).
    pub fn energy(&self, y: &[f64], ydot: &[f64], speed: f64) -> f64 {
        let k = self.k_eff(speed, 0.0);
        let r = self.dim();
        let mut e = 0.0;
        for i in 0..r {
            for j in 0..r {
                e += 0.5 * (ydot[i] * self.m_r[(i, j)] * ydot[j] + y[i] * k[(i, j)] * y[j]);
            }
        }
        e
    }

    /// Static equilibrium on the pulleys at `t = 0` (no load), by active-set iteration on
    /// `K_eff y + D_Aᵀλ = 0`, `D_A y = s_A` (start: all candidates active; release tensile
    /// contacts, activate penetrations). Sets [`Self::active`] and returns `y`.
    pub fn static_equilibrium(&mut self) -> Result<Vec<f64>, FlowError> {
        let (s, a) = self.motion.prescribed(0.0).unwrap_or((0.0, 0.0));
        let k = self.k_eff(s, a);
        let r = self.dim();
        self.active.iter_mut().for_each(|x| *x = true);
        for _ in 0..(4 * self.candidates.len() + 10) {
            let act = self.active_list();
            let na = act.len();
            let mut kkt = Mat::<f64>::zeros(r + na, r + na);
            let mut rhs = Mat::<f64>::zeros(r + na, 1);
            for i in 0..r {
                for j in 0..r {
                    kkt[(i, j)] = k[(i, j)];
                }
            }
            for (row, &c) in act.iter().enumerate() {
                let node = self.candidates[c].node;
                for j in 0..r {
                    kkt[(r + row, j)] = self.t[(node, j)];
                    kkt[(j, r + row)] = self.t[(node, j)];
                }
                rhs[(r + row, 0)] = self.candidates[c].surface;
            }
            let sol = kkt.partial_piv_lu().solve(&rhs);
            let y: Vec<f64> = (0..r).map(|i| sol[(i, 0)]).collect();
            let mut changed = false;
            let scale = 1e-9
                * self
                    .candidates
                    .iter()
                    .map(|c| c.surface.abs())
                    .fold(1e-12, f64::max);
            // Release the most tensile contact, if any.
            if let Some((row, _)) = act
                .iter()
                .enumerate()
                .map(|(row, _)| (row, -sol[(r + row, 0)]))
                .filter(|(_, p)| *p < 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1))
            {
                self.active[act[row]] = false;
                changed = true;
            }
            if !changed {
                for c in 0..self.candidates.len() {
                    if !self.active[c] && self.gap(c, &y) < -scale {
                        self.active[c] = true;
                        changed = true;
                    }
                }
            }
            if !changed {
                return Ok(y);
            }
        }
        Err(invalid(
            "wrapped string: static equilibrium",
            "the active-set iteration did not settle",
        ))
    }
}

impl SecondOrderSystem for ContactString {
    fn n_q(&self) -> usize {
        self.dim()
    }

    fn n_c(&self) -> usize {
        self.active.iter().filter(|a| **a).count()
    }

    fn mass_is_constant(&self) -> bool {
        true
    }

    fn dof_name(&self, dof: usize) -> String {
        format!("{} {dof}", self.coordinate_kind)
    }

    fn constraint_name(&self, row: usize) -> String {
        match self.active_list().get(row) {
            Some(&c) => format!(
                "contact of node {} (x = {:.4} m) with pulley {}",
                self.candidates[c].node, self.candidates[c].x, self.candidates[c].pulley
            ),
            None => format!("constraint {row}"),
        }
    }

    fn mass(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        Ok(SysMatrix::Dense(self.m_r.clone()))
    }

    fn forces(
        &self, t: f64, q: &[f64], v: &[f64], f: &mut [f64], _ws: &mut Workspace,
    ) -> Result<(), MbdError> {
        let (s, a) = self.motion.prescribed(t).ok_or_else(|| MbdError::Model {
            t,
            message: "axial motion must be prescribed".into(),
        })?;
        let r = self.dim();
        for i in 0..r {
            let mut x = 0.0;
            for j in 0..r {
                x -= (self.k_r[(i, j)] + a * self.mx_r[(i, j)] + s * s * self.mxx_r[(i, j)]) * q[j]
                    + 2.0 * s * self.mx_r[(i, j)] * v[j];
            }
            f[i] = x;
        }
        if let Some((node, l)) = self.load {
            let fl = l.amplitude * (2.0 * std::f64::consts::PI * l.frequency * t).sin();
            for i in 0..r {
                f[i] += self.t[(node, i)] * fl;
            }
        }
        Ok(())
    }

    fn constraint_residual(&self, _t: f64, q: &[f64], phi: &mut [f64]) -> Result<(), MbdError> {
        for (row, c) in self.active_list().into_iter().enumerate() {
            phi[row] = self.gap(c, q);
        }
        Ok(())
    }

    fn constraint_jacobian(&self, _t: f64, _q: &[f64]) -> Result<SysMatrix, MbdError> {
        let act = self.active_list();
        let r = self.dim();
        Ok(SysMatrix::Dense(Mat::from_fn(act.len(), r, |row, j| {
            self.t[(self.candidates[act[row]].node, j)]
        })))
    }
}

/// `(t, q, v, contact forces)` of the last evaluated state.
type CachedForces = (f64, Vec<f64>, Vec<f64>, Vec<f64>);

/// Settings of the active-set simulation.
#[derive(
    Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(deny_unknown_fields, default)]
pub struct ContactConfig {
    /// Penetration that activates a contact \[m\].
    pub gap_tol: f64,
    /// Tensile contact force that releases a contact \[N\].
    pub force_tol: f64,
    /// Relative tolerance of Dormand–Prince \[-\].
    pub rtol: f64,
    /// Absolute tolerance of Dormand–Prince \[units of the state: m, m/s\].
    pub atol: f64,
    /// Maximum number of contact events.
    pub max_events: usize,
}

impl Default for ContactConfig {
    fn default() -> Self {
        Self {
            gap_tol: 1e-9,
            force_tol: 1e-9,
            rtol: 1e-8,
            atol: 1e-11,
            max_events: 100_000,
        }
    }
}

/// Most contact events of one run (`max_events` is bounded by it before the run).
pub const MAX_CONTACT_EVENTS: usize = 10_000_000;

/// Loosest relative tolerance of Dormand–Prince (looser is no integration) and the tightest
/// (below it the step control chases round-off: mbd-core's minimum step stops the run).
pub const RTOL_RANGE: (f64, f64) = (1e-13, 0.1);

impl mbd_core::validate::Validate for ContactConfig {
    fn validate(&self) -> Result<(), mbd_core::validate::InvalidField> {
        use mbd_core::validate::check;
        check::non_negative("gap_tol", self.gap_tol, "m")?;
        check::non_negative("force_tol", self.force_tol, "N")?;
        check::within("rtol", self.rtol, RTOL_RANGE.0, RTOL_RANGE.1, "")?;
        check::non_negative("atol", self.atol, "")?;
        check::size("max_events", self.max_events, 1, MAX_CONTACT_EVENTS)?;
        Ok(())
    }
}

/// One contact switch.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContactEvent {
    /// Time \[s\].
    pub t: f64,
    /// Candidate index.
    pub candidate: usize,
    /// Mesh node.
    pub node: usize,
    /// `true`: activation (impact), `false`: release.
    pub activated: bool,
    /// Kinetic energy removed by the plastic impact \[J\] (0 for a release).
    pub impact_loss: f64,
}

/// Result of [`simulate_contact`].
#[derive(Debug, Clone)]
pub struct ContactRun {
    /// Final state.
    pub state: State,
    /// Contact switches in time order.
    pub events: Vec<ContactEvent>,
    /// Integrator statistics.
    pub stats: mbd_core::Stats,
}

fn kinetic(sys: &ContactString, v: &[f64]) -> f64 {
    let r = sys.dim();
    let mut e = 0.0;
    for i in 0..r {
        for j in 0..r {
            e += 0.5 * v[i] * sys.m_r[(i, j)] * v[j];
        }
    }
    e
}

/// Integrates the wrapped string from `state0` to `t_end` \[s\] with Dormand–Prince and event
/// location (mbd-core), switching the active set at every located event (activation with a
/// plastic impact, release on a tensile multiplier). `observer` sees every accepted step and
/// event state together with the active set in force; it may answer `ControlFlow::Break(())`
/// ([`mbd_core::integrators::Proceed`]) to stop the run there (a cancelled run: the run so far
/// is returned).
pub fn simulate_contact<R: mbd_core::integrators::Proceed>(
    sys: &mut ContactString, state0: State, t_end: f64, settings: &ContactConfig,
    mut observer: impl FnMut(&ContactString, &State) -> R,
) -> Result<ContactRun, FlowError> {
    let stab = Stabilization {
        project: true,
        projection_tol: 1e-12,
        ..Default::default()
    };
    let dopri = DormandPrince {
        rtol: settings.rtol,
        atol: settings.atol,
        stabilization: stab,
        ..Default::default()
    };
    let mut state = state0;
    let mut events = Vec::new();
    let mut stats = mbd_core::Stats::default();
    let nc = sys.candidates.len();
    // The initial state may not match the active set (e.g. a pluck next to a contact node).
    settle(sys, &mut state, settings, &mut events)?;
    while state.t < t_end {
        let snapshot = sys.clone();
        // All release events share one index-1 solve per distinct state.
        let cache: std::cell::RefCell<Option<CachedForces>> = std::cell::RefCell::new(None);
        let forces_at = |st: &State| -> Option<Vec<f64>> {
            if let Some((t, q, v, p)) = cache.borrow().as_ref()
                && *t == st.t
                && *q == st.q
                && *v == st.v
            {
                return Some(p.clone());
            }
            let p = snapshot.contact_forces(st).ok()?;
            *cache.borrow_mut() = Some((st.t, st.q.clone(), st.v.clone(), p.clone()));
            Some(p)
        };
        let forces_at = &forces_at;
        let evs: Vec<Event<'_>> = (0..nc)
            .map(|c| {
                let s = &snapshot;
                if s.active[c] {
                    let tol = settings.force_tol;
                    Event {
                        name: format!("release {c}"),
                        g: Box::new(move |st: &State| match forces_at(st) {
                            Some(p) => p[c] + tol,
                            None => 1.0,
                        }),
                        direction: -1,
                        action: EventAction::Stop,
                    }
                } else {
                    let tol = settings.gap_tol;
                    Event {
                        name: format!("contact {c}"),
                        g: Box::new(move |st: &State| s.gap(c, &st.q) + tol),
                        direction: -1,
                        action: EventAction::Stop,
                    }
                }
            })
            .collect();
        let mut stop = false;
        let sol = dopri.integrate_with_events(&snapshot, state.clone(), t_end, &evs, |st| {
            let go_on = observer(&snapshot, st).proceed();
            stop |= !go_on;
            if go_on {
                std::ops::ControlFlow::Continue(())
            } else {
                std::ops::ControlFlow::Break(())
            }
        })?;
        drop(evs);
        stats.accumulate(&sol.stats);
        state = sol.state;
        if stop {
            break;
        }
        let Some(rec) = sol.events.first() else { break };
        if events.len() >= settings.max_events {
            return Err(FlowError::Mbd(MbdError::Model {
                t: state.t,
                message: format!(
                    "more than {} contact events (chattering?)",
                    settings.max_events
                ),
            }));
        }
        let c = rec.index;
        let was_active = sys.active[c];
        sys.active[c] = !was_active;
        let mut loss = 0.0;
        if !was_active {
            // Plastic impact: project the velocities onto D_A ẏ = 0 (mbd-core), then the
            // positions onto the surface.
            let before = kinetic(sys, &state.v);
            project_positions(&*sys, &mut state, &stab)?;
            project_velocities(&*sys, &mut state)?;
            loss = before - kinetic(sys, &state.v);
        }
        events.push(ContactEvent {
            t: state.t,
            candidate: c,
            node: sys.candidates[c].node,
            activated: !was_active,
            impact_loss: loss,
        });
        settle(sys, &mut state, settings, &mut events)?;
        observer(sys, &state);
    }
    Ok(ContactRun {
        state,
        events,
        stats,
    })
}

/// Makes the active set consistent with `state`: releases tensile contacts one at a time (most
/// tensile first), then activates penetrating candidates with a plastic impact, until nothing
/// changes.
fn settle(
    sys: &mut ContactString, state: &mut State, settings: &ContactConfig,
    events: &mut Vec<ContactEvent>,
) -> Result<(), FlowError> {
    let stab = Stabilization {
        project: true,
        projection_tol: 1e-12,
        ..Default::default()
    };
    let nc = sys.candidates.len();
    for _ in 0..(4 * nc + 4) {
        let p = sys.contact_forces(state)?;
        let worst = (0..nc)
            .filter(|&k| sys.active[k])
            .min_by(|&a, &b| p[a].total_cmp(&p[b]));
        if let Some(k) = worst.filter(|&k| p[k] < -settings.force_tol) {
            sys.active[k] = false;
            events.push(ContactEvent {
                t: state.t,
                candidate: k,
                node: sys.candidates[k].node,
                activated: false,
                impact_loss: 0.0,
            });
            continue;
        }
        let pen: Vec<usize> = (0..nc)
            .filter(|&k| !sys.active[k] && sys.gap(k, &state.q) < -settings.gap_tol)
            .collect();
        if pen.is_empty() {
            return Ok(());
        }
        let before = kinetic(sys, &state.v);
        for &k in &pen {
            sys.active[k] = true;
        }
        project_positions(&*sys, state, &stab)?;
        project_velocities(&*sys, state)?;
        let loss = before - kinetic(sys, &state.v);
        for (i, &k) in pen.iter().enumerate() {
            events.push(ContactEvent {
                t: state.t,
                candidate: k,
                node: sys.candidates[k].node,
                activated: true,
                impact_loss: if i == 0 { loss } else { 0.0 },
            });
        }
    }
    Err(FlowError::Mbd(MbdError::Model {
        t: state.t,
        message: "the contact active set does not settle (chattering)".into(),
    }))
}

/// `Tᵀ M u` helper: generalized coordinates of a nodal field in the span of `T` (least squares
/// in the `TᵀMT` metric).
pub fn coordinates_of(
    sys: &ContactString, mass: MatRef<'_, f64>, u: &[f64],
) -> Result<Vec<f64>, FlowError> {
    let r = sys.dim();
    if u.len() != sys.t.nrows() {
        return Err(invalid(
            "nodal field",
            format!("{} entries, expected {}", u.len(), sys.t.nrows()),
        ));
    }
    let mu = Mat::from_fn(u.len(), 1, |i, _| {
        (0..u.len()).map(|j| mass[(i, j)] * u[j]).sum::<f64>()
    });
    let rhs = sys.t.transpose() * &mu;
    let llt = sys
        .m_r
        .llt(faer::Side::Lower)
        .map_err(|e| FlowError::LinearAlgebra {
            what: "TᵀMT".into(),
            reason: format!("{e:?}"),
        })?;
    let y = llt.solve(&rhs);
    Ok((0..r).map(|i| y[(i, 0)]).collect())
}
