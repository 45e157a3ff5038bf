//! Steady-state force and moment characteristics of the rolling tire on a flat road (issue 38,
//! items 1 and 5): the side force `F_y(α)` and aligning moment `M_z(α)` over a sweep of slip
//! angles, the longitudinal force `F_x(κ)` over a sweep of drive/brake torques and over a
//! sweep of prescribed longitudinal slips (the spin rate held at `Ω = (1 + κ) Ω₀`, through and
//! beyond the peak of `F_x`, with the reaction torque as an output), and the camber thrust
//! `F_y(γ)` with `M_x(γ)`, `M_z(γ)` over a sweep of camber angles, each point settled on the
//! same rig and time stepper as the cleat test ([`crate::rig::run_cleat`] without a cleat,
//! [`crate::rig::WheelInputs`] set per point). The road may be a height grid
//! (`rig.ground.grid_file`: the loads are then means over the rough road).
//!
//! With camber the loads are in the W-axis orientation (z along the road normal,
//! [`WheelLoads`]); the camber sign is that of [`crate::rig::WheelInputs::camber_deg`] (ISO
//! 8855: positive when the top of the wheel leans to the right).
//!
//! Frame and signs: the ISO 8855 wheel frame of [`WheelLoads`] (x forward, y left, z up, origin
//! at the wheel centre). Slip definitions of Pacejka, *Tire and Vehicle Dynamics* (§1.2):
//! slip angle `tan α = −V_y/|V_x|`, longitudinal slip `κ = −(V_x − Ω R_e)/V_x` with the
//! effective rolling radius `R_e = V_x/Ω₀` of the free-rolling wheel (spin rate `Ω₀` of the
//! free-rolling point), so `κ = Ω/Ω₀ − 1`. Cornering stiffness `C_Fα = dF_y/dα` at α = 0
//! \[N/rad\], pneumatic trail `t = −M_z/F_y` \[m\].
//!
//! Each point starts from the free-rolling steady state of the preload (`preload_rolling`),
//! applies its input at `t = 0` and rolls for `point_time`; its loads are the means over the
//! last `average_time`.

use crate::error::TireError;
use crate::ground::GroundKind;
use crate::reduced::ReducedTire;
use crate::rig::{MAX_RIG_STEPS, RigConfig, run_cleat_observed};
use crate::rolling::WheelLoads;
use crate::source::TireSource;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Most points of one steady sweep (slip angles plus torques plus the free-rolling point).
pub const MAX_STEADY_POINTS: usize = 1000;

/// Largest longitudinal slip of [`SteadyStudyConfig::slip_ratios`] \[-\].
pub const MAX_SLIP_RATIO: f64 = 10.0;

/// Default time step of the steady study \[s\]: 0.2 ms, the cleat rig's. Since the contact
/// sticks on the material velocity (Ribaric (7.10), issue 38 item 5) the steady forces no longer
/// depend on the step: on the default tire F_y(0.05°), F_y(0.2°) agree to 1.3e-5 from 0.2 to
/// 0.025 ms, and the whole default sweep at 0.2 ms agrees with 0.05 ms within 0.07 % on every
/// force, 0.5 % on the spin torque at full sliding and 0.3 % on the relaxation length
/// (BENCHMARKS, "Steady characteristics: convergence in contact nodes"). (0.05 ms until then.)
pub const DEFAULT_TIME_STEP: f64 = 2e-4;

/// Configuration of the steady-state study (`flowmbd-tire steady`).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct SteadyStudyConfig {
    /// The tire.
    pub tire: TireSource,
    /// The rig: load, speed, friction, damping and integration (default: flat road without
    /// cleat at 60 km/h). Its `settle_time`, `record_time` and `wheel` are replaced per point
    /// (`point_time`, 0 and the point's input); `ground.cleat` must be off and
    /// `ground.obstacles` empty (a height-grid road is allowed: its `x = 0` passes the patch
    /// centre at the end of each point, so each point rolls over the grid's stretch
    /// `−v point_time ≤ x ≤ 0`).
    pub rig: RigConfig,
    /// Slip angles of the side-force sweep \[deg\] (each at zero drive torque; within ±45°).
    /// The cornering stiffness is the secant over the smallest mirrored pair
    /// ([`cornering_stiffness`]): keep that pair in the linear range (the coarse test tire
    /// slides nearly over its whole patch at 1°, linear to about 0.2°).
    pub slip_angles_deg: Vec<f64>,
    /// Drive (positive) or brake (negative) torques of the longitudinal sweep \[N·m\] (each at
    /// zero slip angle).
    pub drive_torques_n_m: Vec<f64>,
    /// Longitudinal slips κ of the prescribed-spin sweep \[-\] (each at zero slip angle and
    /// no torque; within \[−1, 10\]): the spin rate is held at `Ω = (1 + κ) Ω₀` with `Ω₀` of
    /// the free-rolling point ([`crate::rig::WheelInputs::spin_rate`]), so `F_x(κ)` is
    /// obtained through and beyond its peak (a torque sweep cannot pass the peak: a torque
    /// above it spins the wheel up without a steady state).
    pub slip_ratios: Vec<f64>,
    /// Camber angles of the camber sweep \[deg\] (each at zero slip angle and torque; within
    /// ±[`crate::rig::MAX_CAMBER_DEG`]; none by default). Each runs the full model.
    pub camber_angles_deg: Vec<f64>,
    /// Simulated time of each point from the free-rolling start \[s\].
    pub point_time: f64,
    /// The point's loads are the means over its last `average_time` \[s\].
    pub average_time: f64,
}

impl Default for SteadyStudyConfig {
    fn default() -> Self {
        let mut rig = RigConfig::default();
        rig.ground.kind = GroundKind::Road;
        rig.ground.cleat = false;
        // the step chosen when the small-slip characteristics depended on it (BENCHMARKS,
        // "Steady characteristics"): since the contact's stick condition carries the transport
        // term (2026-12-06) F_y(0.2°) on the default tire is 767.847, 767.840, 767.838 and
        // 767.837 N at 0.2, 0.1, 0.05 and 0.025 ms, so the rig's 0.2 ms would do as well
        rig.rolling.time_step = DEFAULT_TIME_STEP;
        Self {
            tire: TireSource::default(),
            rig,
            slip_angles_deg: vec![-0.2, 0.2, 1.0, 4.0],
            drive_torques_n_m: vec![-1000.0, 1000.0],
            slip_ratios: vec![-0.2, -0.05, -0.01, 0.01, 0.05, 0.2],
            camber_angles_deg: Vec::new(),
            point_time: 0.3,
            average_time: 0.05,
        }
    }
}

impl mbd_core::config::PartialRules for SteadyStudyConfig {}

impl Validate for SteadyStudyConfig {
    /// The tire, the rig (`rig.…`), finite slip angles within ±45°, torques and camber angles
    /// within ±30°, at most [`MAX_STEADY_POINTS`] points, a positive `point_time` of at least
    /// 2 steps (and at most the rig's step limit), `average_time` in (0, `point_time`], no
    /// cleat or obstacles.
    fn validate(&self) -> Result<(), InvalidField> {
        self.tire.validate_within("tire")?;
        self.rig.validate_within("rig")?;
        if self.rig.ground.cleat {
            return Err(InvalidField::new(
                "rig.ground.cleat",
                "must be false: the steady study rolls on the plain drum or road",
            ));
        }
        if !self.rig.ground.obstacles.is_empty() {
            return Err(InvalidField::new(
                "rig.ground.obstacles",
                "must be empty: the steady study rolls on the plain drum or road (or a \
                 height-grid road)",
            ));
        }
        let n = self.slip_angles_deg.len()
            + self.drive_torques_n_m.len()
            + self.camber_angles_deg.len()
            + self.slip_ratios.len()
            + 1;
        check::size("slip_angles_deg", n, 1, MAX_STEADY_POINTS)?;
        for (i, a) in self.slip_angles_deg.iter().enumerate() {
            let max = crate::rig::MAX_SLIP_ANGLE_DEG;
            check::within(&format!("slip_angles_deg[{i}]"), *a, -max, max, "deg")?;
        }
        for (i, t) in self.drive_torques_n_m.iter().enumerate() {
            check::finite(&format!("drive_torques_n_m[{i}]"), *t)?;
        }
        for (i, k) in self.slip_ratios.iter().enumerate() {
            check::within(&format!("slip_ratios[{i}]"), *k, -1.0, MAX_SLIP_RATIO, "")?;
        }
        for (i, g) in self.camber_angles_deg.iter().enumerate() {
            let max = crate::rig::MAX_CAMBER_DEG;
            check::within(&format!("camber_angles_deg[{i}]"), *g, -max, max, "deg")?;
        }
        check::positive("point_time", self.point_time, "s")?;
        check::positive("average_time", self.average_time, "s")?;
        let h = self.rig.rolling.time_step;
        if self.point_time < 2.0 * h {
            return Err(InvalidField::new(
                "point_time",
                format!(
                    "{} s is less than 2 steps of rig.rolling.time_step = {} s",
                    check::show(self.point_time),
                    check::show(h)
                ),
            ));
        }
        if self.point_time / h > MAX_RIG_STEPS {
            return Err(InvalidField::new(
                "point_time",
                format!(
                    "{} s is more than {MAX_RIG_STEPS:e} steps of {} s",
                    check::show(self.point_time),
                    check::show(h)
                ),
            ));
        }
        if self.average_time > self.point_time {
            return Err(InvalidField::new(
                "average_time",
                format!(
                    "{} s is longer than point_time = {} s",
                    check::show(self.average_time),
                    check::show(self.point_time)
                ),
            ));
        }
        Ok(())
    }
}

/// One settled point of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SteadyPoint {
    /// Slip angle α \[deg\].
    pub slip_angle_deg: f64,
    /// Drive torque \[N·m\] (the input; 0 at a prescribed-spin point).
    pub drive_torque_n_m: f64,
    /// Mean torque applied to the wheel about +y \[N·m\]: the drive torque, or at a
    /// prescribed-spin point the reaction torque that holds the spin
    /// ([`crate::RollingTire::spin_torque`]).
    pub spin_torque_n_m: f64,
    /// Camber angle γ \[deg\].
    pub camber_deg: f64,
    /// Longitudinal slip `κ = Ω/Ω₀ − 1` against the free-rolling spin rate `Ω₀` \[-\].
    pub kappa: f64,
    /// Mean spin rate Ω \[rad/s\].
    pub spin_rad_per_s: f64,
    /// Mean loads over the last `average_time` (ISO 8855 wheel frame; with camber the W-axis
    /// orientation, [`WheelLoads`]).
    pub loads: WheelLoads,
    /// Torque balance of the wheel about its axle \[N·m\]: `spin_torque_n_m + M_y`, the torque
    /// applied to the wheel plus the moment of the contact forces about the axle (ISO 8855
    /// `M_y`, deformed positions). Zero in a steady state of a model whose elastic forces carry
    /// no moment under a rigid rotation; the reduced tire's rim moment (Ribaric (7.2),
    /// `K_θ z`) transmits only [`SteadyResult::rim_moment_transfer`] of the contact moment, so
    /// here it is about `−(1 − transfer)` of `−M_y` (see that field).
    pub torque_residual_n_m: f64,
    /// Largest minus smallest `F_y` over the averaging window \[N\] (how settled the point is;
    /// likewise for the torque points' `F_x`).
    pub spread_n: f64,
    /// Sum of the normal contact forces at the end \[N\].
    pub normal_sum_n: f64,
    /// Coulomb utilisation of the contact forces over the averaging window \[-\]:
    /// `(|mean Σfᵢ,x|, |mean Σfᵢ,y|)/(μ mean Σλᵢ)` of the friction forces `fᵢ` (wheel frame
    /// x, y) and normal forces `λᵢ` of the contact nodes. Each node obeys `|fᵢ| ≤ μ λᵢ`
    /// (Coulomb's law), so both are at most 1 up to the contact solve's tolerance; the
    /// spindle's `F_x/(μ F_z)` and `F_y/(μ F_z)` can exceed 1 by the tire's inertia over the
    /// window (its centre-of-mass oscillation is in the spindle force, not in the contact).
    pub utilisation: [f64; 2],
    /// Contact nodes in contact at the end.
    pub active_nodes: usize,
    /// Lateral relaxation length σ_α \[m\] of a slip-angle point ([`relaxation_length`]):
    /// the distance rolled after the step in α until `F_y` first reaches `1 − 1/e` of its
    /// settled mean; `None` at the torque and free-rolling points, or where `F_y` is zero or
    /// does not get there.
    pub relaxation_length_m: Option<f64>,
}

/// Result of the steady-state sweep.
#[derive(Debug, Clone, Serialize)]
pub struct SteadyResult {
    /// The free-rolling, straight-ahead point (α = 0, no torque): the reference `Ω₀` of κ and
    /// the cleat study's steady rolling (its `F_x`, `F_z` are the cleat path's spindle forces).
    pub free_rolling: SteadyPoint,
    /// The slip-angle points in the order of `slip_angles_deg`.
    pub slip: Vec<SteadyPoint>,
    /// The torque points in the order of `drive_torques_n_m`.
    pub torque: Vec<SteadyPoint>,
    /// The prescribed-spin points in the order of `slip_ratios`.
    pub prescribed: Vec<SteadyPoint>,
    /// The camber points in the order of `camber_angles_deg`.
    pub camber: Vec<SteadyPoint>,
    /// Model stepped at the slip-angle points (full model when α ≠ 0).
    pub symmetry: String,
    /// Model stepped at the camber points (full model when γ ≠ 0; empty without them).
    pub camber_symmetry: String,
    /// Share of the moment of a contact force about the axle that the reduced tire's rim
    /// moment carries \[-\] ([`rim_moment_transfer`]): 1 for a tire whose stiffness matrix
    /// has no moment under a rigid rotation about the axle.
    pub rim_moment_transfer: f64,
}

/// The share of the moment of a longitudinal contact force about the axle that reaches the rim
/// through the reduced tire's rim moment (Ribaric (7.2): `n_K^θ = K^θ δ`, the row `k_θ` of
/// [`ReducedTire::kt`]) \[-\]: the static reduced solve `K_z z = T_cᵀ f` of a unit force
/// along x at the lowest contact node `s` gives the rim moment `k_θ·z`, compared with the
/// force's moment `s_z f_x` about the axle: `−k_θ·z/s_z`. Equilibrium of the tire makes it 1
/// when the elastic forces of a rigid rotation about the axle have no moment (`r_rotᵀ K r = 0`
/// for every `r`); the generated tire's inflation prestress (`fe_model::generate::tire`:
/// the geometric stiffness of the membrane forces, without the stiffness of the pressure load
/// that follows the surface) breaks that, and the rim then carries less than the contact
/// moment (0.85 on the coarse test tire at 262 kPa, 1 to 1e-12 without pressure). In a steady
/// state the torque on the wheel is the rim moment, so `spin_torque ≈ transfer · (−M_y)`
/// ([`SteadyPoint::torque_residual_n_m`]). Errors: a singular `K_z`.
pub fn rim_moment_transfer(red: &ReducedTire) -> Result<f64, TireError> {
    let i = (0..red.n_contact())
        .min_by(|&a, &b| red.contact_positions[a][2].total_cmp(&red.contact_positions[b][2]))
        .ok_or_else(|| crate::error::invalid("tire", "the reduced tire has no contact node"))?;
    let nz = red.n_z();
    let rhs = faer::Mat::from_fn(nz, 1, |j, _| red.tc[(3 * i, j)]);
    let z = faer::linalg::solvers::Solve::solve(&red.k.partial_piv_lu(), &rhs);
    if !z.as_ref().is_all_finite() {
        return Err(crate::error::linalg("reduced stiffness K_z", "singular"));
    }
    let rim: f64 = (0..nz).map(|j| red.kt[(1, j)] * z[(j, 0)]).sum();
    Ok(-rim / red.contact_positions[i][2])
}

/// Cornering stiffness `C_Fα = dF_y/dα` at α = 0 \[N/rad\] from the points `(α [deg], F_y)`
/// with the free-rolling point `(0, fy0)`: the central difference over `±α₁` for the smallest
/// `|α₁| > 0` whose mirror is in the sweep, else the one-sided difference to α = 0 over the
/// smallest `|α|`. `None` without a non-zero slip angle.
pub fn cornering_stiffness(points: &[(f64, f64)], fy0: f64) -> Option<f64> {
    let nz: Vec<&(f64, f64)> = points.iter().filter(|p| p.0 != 0.0).collect();
    let smallest = |ps: &[&(f64, f64)]| {
        ps.iter()
            .copied()
            .min_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
            .copied()
    };
    let paired: Vec<&(f64, f64)> = nz
        .iter()
        .copied()
        .filter(|p| p.0 > 0.0 && nz.iter().any(|q| q.0 == -p.0))
        .collect();
    if let Some(p) = smallest(&paired) {
        let q = nz.iter().find(|q| q.0 == -p.0)?;
        return Some((p.1 - q.1) / (2.0 * p.0.to_radians()));
    }
    let p = smallest(&nz)?;
    Some((p.1 - fy0) / p.0.to_radians())
}

/// Longitudinal slip stiffness `C_Fκ = dF_x/dκ` at κ = 0 \[N\] (Pacejka, *Tire and Vehicle
/// Dynamics*, §1.3, `C_Fκ`) from the points `(κ, F_x)` with the free-rolling point
/// `(0, fx0)`: the secant between the smallest positive and the smallest negative κ when both
/// exist, else the one-sided difference to κ = 0 over the smallest `|κ|`. `None` without a
/// point of non-zero κ.
pub fn slip_stiffness(points: &[(f64, f64)], fx0: f64) -> Option<f64> {
    let nearest = |sign: f64| {
        points
            .iter()
            .filter(|p| p.0 * sign > 0.0)
            .min_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
            .copied()
    };
    match (nearest(1.0), nearest(-1.0)) {
        (Some(p), Some(q)) => Some((p.1 - q.1) / (p.0 - q.0)),
        (Some(p), None) | (None, Some(p)) => Some((p.1 - fx0) / p.0),
        (None, None) => None,
    }
}

/// Relaxation length \[m\] of a force history after a step input at distance 0: the distance
/// `s` at which the force `f(s)` first reaches `1 − 1/e` of its settled value `f_ss`, linear
/// between samples (the exponential lag `f = f_ss (1 − e^{−s/σ})` of the stretched-string
/// model reaches it at `s = σ`: Pacejka, *Tire and Vehicle Dynamics*, §5.3 and §7.2, (7.4)).
/// `history` holds `(s [m], f [N])` in rolling order. `None` when `f_ss` is zero or not
/// finite or the force does not get there.
pub fn relaxation_length(history: &[(f64, f64)], f_ss: f64) -> Option<f64> {
    if f_ss == 0.0 || !f_ss.is_finite() {
        return None;
    }
    let target = 1.0 - (-1.0f64).exp();
    let mut prev = (0.0, 0.0);
    for &(s, f) in history {
        let r = f / f_ss;
        if r >= target {
            let r0 = prev.1 / f_ss;
            return Some(prev.0 + (s - prev.0) * (target - r0) / (r - r0));
        }
        prev = (s, f);
    }
    None
}

impl SteadyResult {
    /// Longitudinal slip stiffness `dF_x/dκ` at κ = 0 \[N\] ([`slip_stiffness`]) of the
    /// prescribed-spin points (κ set, not reached through the wheel's inertia), or of the
    /// torque points when there are none.
    pub fn slip_stiffness(&self) -> Option<f64> {
        let points = if self.prescribed.is_empty() {
            &self.torque
        } else {
            &self.prescribed
        };
        let pts: Vec<(f64, f64)> = points.iter().map(|p| (p.kappa, p.loads.fx)).collect();
        slip_stiffness(&pts, self.free_rolling.loads.fx)
    }

    /// Lateral relaxation length σ_α \[m\] at small slip: the mean of
    /// [`SteadyPoint::relaxation_length_m`] over the slip-angle points of the smallest `|α|`
    /// (the cornering stiffness's pair), `None` without one.
    pub fn relaxation_length(&self) -> Option<f64> {
        let a = self
            .slip
            .iter()
            .filter(|p| p.slip_angle_deg != 0.0)
            .map(|p| p.slip_angle_deg.abs())
            .min_by(f64::total_cmp)?;
        let v: Vec<f64> = self
            .slip
            .iter()
            .filter(|p| p.slip_angle_deg.abs() == a)
            .filter_map(|p| p.relaxation_length_m)
            .collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    }

    /// Cornering stiffness `dF_y/dα` at α = 0 \[N/rad\] ([`cornering_stiffness`]).
    pub fn cornering_stiffness(&self) -> Option<f64> {
        let pts: Vec<(f64, f64)> = self
            .slip
            .iter()
            .map(|p| (p.slip_angle_deg, p.loads.fy))
            .collect();
        cornering_stiffness(&pts, self.free_rolling.loads.fy)
    }

    /// Camber stiffness `dF_y/dγ` at γ = 0 \[N/rad\] (W-axis `F_y`; [`cornering_stiffness`] on
    /// the camber points: the central difference over the smallest mirrored pair). `None`
    /// without a non-zero camber angle.
    pub fn camber_stiffness(&self) -> Option<f64> {
        let pts: Vec<(f64, f64)> = self
            .camber
            .iter()
            .map(|p| (p.camber_deg, p.loads.fy))
            .collect();
        cornering_stiffness(&pts, self.free_rolling.loads.fy)
    }

    /// Pneumatic trail `t = −M_z/F_y` \[m\] of each slip-angle point (`NaN` where `F_y = 0`).
    pub fn pneumatic_trail(&self) -> Vec<f64> {
        self.slip
            .iter()
            .map(|p| {
                if p.loads.fy == 0.0 {
                    f64::NAN
                } else {
                    -p.loads.mz / p.loads.fy
                }
            })
            .collect()
    }
}

/// The wheel inputs of one point: slip angle \[deg\], drive torque \[N·m\], camber \[deg\],
/// prescribed spin rate \[rad/s\] (`None`: free spin).
#[derive(Debug, Clone, Copy)]
struct PointInputs {
    alpha_deg: f64,
    torque: f64,
    camber_deg: f64,
    spin_rate: Option<f64>,
}

/// Run one point: the rig of `cfg` with the wheel inputs `inp`, the means over the last
/// `average_time`. `omega0` is the free-rolling spin rate for κ (`None`: this is the
/// free-rolling point, κ = 0).
fn run_point(
    red: &ReducedTire, cfg: &SteadyStudyConfig, inp: PointInputs, omega0: Option<f64>,
    progress: &mut dyn FnMut(f64),
) -> Result<(SteadyPoint, String), TireError> {
    let PointInputs {
        alpha_deg,
        torque,
        camber_deg,
        spin_rate,
    } = inp;
    let mut rig = cfg.rig.clone();
    rig.settle_time = cfg.point_time;
    rig.record_time = 0.0;
    rig.wheel.slip_angle_deg = alpha_deg;
    rig.wheel.drive_torque = torque;
    rig.wheel.spin_rate = spin_rate;
    rig.wheel.camber_deg = camber_deg;
    // (the rig names its fields relative to itself; the study's root has them under `rig.`)
    // per step: the friction resultant (x, y) and the normal sum of the contact nodes
    let mut contact: Vec<[f64; 3]> = Vec::new();
    let mut observe = |_: usize, sim: &crate::rolling::RollingTire| {
        let st = &sim.state;
        let f = st
            .friction
            .iter()
            .fold([0.0, 0.0], |a, f| [a[0] + f[0], a[1] + f[1]]);
        contact.push([f[0], f[1], sim.total_normal_force()]);
        Ok::<(), TireError>(())
    };
    let r = run_cleat_observed(red, &rig, progress, &mut observe).map_err(|e| match e {
        TireError::Invalid { item, reason } => TireError::Invalid {
            item: format!("rig.{item}"),
            reason,
        },
        other => other,
    })?;
    let t_end = r.samples.last().map_or(0.0, |s| s.t);
    let in_window = |s: &crate::rig::Sample| s.t > t_end - cfg.average_time;
    let w: Vec<_> = r.samples.iter().filter(|s| in_window(s)).collect();
    // the observer ran once per step, as the samples were taken
    let cw: Vec<&[f64; 3]> = r
        .samples
        .iter()
        .zip(&contact)
        .filter(|(s, _)| in_window(s))
        .map(|(_, c)| c)
        .collect();
    let cmean = |k: usize| cw.iter().map(|c| c[k]).sum::<f64>() / cw.len().max(1) as f64;
    let mu_n = cfg.rig.rolling.friction * cmean(2);
    let utilisation = if mu_n > 0.0 {
        [cmean(0).abs() / mu_n, cmean(1).abs() / mu_n]
    } else {
        [0.0, 0.0]
    };
    let n = w.len().max(1) as f64;
    let mean = |f: &dyn Fn(&crate::rig::Sample) -> f64| w.iter().map(|s| f(s)).sum::<f64>() / n;
    let loads = WheelLoads {
        fx: mean(&|s| s.fx),
        fy: mean(&|s| s.fz),
        fz: mean(&|s| s.fy),
        mx: mean(&|s| s.mx),
        my: mean(&|s| s.my),
        mz: mean(&|s| s.mz),
    };
    let spin = mean(&|s| s.spin);
    let spin_torque = mean(&|s| s.spin_torque);
    let longitudinal = torque != 0.0 || spin_rate.is_some();
    let watch = |s: &crate::rig::Sample| if longitudinal { s.fx } else { s.fz };
    let hi = w.iter().map(|s| watch(s)).fold(f64::MIN, f64::max);
    let lo = w.iter().map(|s| watch(s)).fold(f64::MAX, f64::min);
    let last = r.samples.last();
    // the side force against the distance rolled since the step in α (sample times run from
    // −point_time to 0, the input applies from the start)
    let relaxation_length_m = if alpha_deg != 0.0 && torque == 0.0 {
        let v = cfg.rig.speed_kmh / 3.6;
        let history: Vec<(f64, f64)> = r
            .samples
            .iter()
            .map(|s| (v * (s.t + cfg.point_time), s.fz))
            .collect();
        relaxation_length(&history, loads.fy)
    } else {
        None
    };
    Ok((
        SteadyPoint {
            slip_angle_deg: alpha_deg,
            drive_torque_n_m: torque,
            spin_torque_n_m: spin_torque,
            camber_deg,
            kappa: omega0.map_or(0.0, |o| spin / o - 1.0),
            spin_rad_per_s: spin,
            loads,
            torque_residual_n_m: spin_torque + loads.my,
            spread_n: if w.is_empty() { 0.0 } else { hi - lo },
            normal_sum_n: last.map_or(0.0, |s| s.normal_sum),
            utilisation,
            active_nodes: last.map_or(0, |s| s.active),
            relaxation_length_m,
        },
        r.symmetry,
    ))
}

/// Run the steady-state sweep of `cfg` on the reduced tire `red` (module documentation): the
/// free-rolling point, then every slip angle, then every torque. `progress` receives the
/// fraction done (0..1). The settings are validated first ([`SteadyStudyConfig`]'s
/// [`Validate`]; errors name the field relative to the study's root).
pub fn run_steady(
    red: &ReducedTire, cfg: &SteadyStudyConfig, progress: &mut dyn FnMut(f64),
) -> Result<SteadyResult, TireError> {
    cfg.validate()?;
    let total = (1
        + cfg.slip_angles_deg.len()
        + cfg.drive_torques_n_m.len()
        + cfg.slip_ratios.len()
        + cfg.camber_angles_deg.len()) as f64;
    let mut k = 0.0;
    let at = |alpha_deg, torque, camber_deg, spin_rate| PointInputs {
        alpha_deg,
        torque,
        camber_deg,
        spin_rate,
    };
    let (free, _) = run_point(red, cfg, at(0.0, 0.0, 0.0, None), None, &mut |f| {
        progress(f / total)
    })?;
    k += 1.0;
    let omega0 = free.spin_rad_per_s;
    let mut slip = Vec::with_capacity(cfg.slip_angles_deg.len());
    let mut symmetry = String::new();
    for &a in &cfg.slip_angles_deg {
        let (p, s) = run_point(red, cfg, at(a, 0.0, 0.0, None), Some(omega0), &mut |f| {
            progress((k + f) / total)
        })?;
        k += 1.0;
        if a != 0.0 || symmetry.is_empty() {
            symmetry = s;
        }
        slip.push(p);
    }
    let mut torque = Vec::with_capacity(cfg.drive_torques_n_m.len());
    for &t in &cfg.drive_torques_n_m {
        let (p, _) = run_point(red, cfg, at(0.0, t, 0.0, None), Some(omega0), &mut |f| {
            progress((k + f) / total)
        })?;
        k += 1.0;
        torque.push(p);
    }
    let mut prescribed = Vec::with_capacity(cfg.slip_ratios.len());
    for &kappa in &cfg.slip_ratios {
        let spin = Some((1.0 + kappa) * omega0);
        let (p, _) = run_point(red, cfg, at(0.0, 0.0, 0.0, spin), Some(omega0), &mut |f| {
            progress((k + f) / total)
        })?;
        k += 1.0;
        prescribed.push(p);
    }
    let mut camber = Vec::with_capacity(cfg.camber_angles_deg.len());
    let mut camber_symmetry = String::new();
    for &g in &cfg.camber_angles_deg {
        let (p, s) = run_point(red, cfg, at(0.0, 0.0, g, None), Some(omega0), &mut |f| {
            progress((k + f) / total)
        })?;
        k += 1.0;
        if g != 0.0 || camber_symmetry.is_empty() {
            camber_symmetry = s;
        }
        camber.push(p);
    }
    progress(1.0);
    Ok(SteadyResult {
        free_rolling: free,
        slip,
        torque,
        prescribed,
        camber,
        symmetry,
        camber_symmetry,
        rim_moment_transfer: rim_moment_transfer(red)?,
    })
}

/// Summary of the steady-state study (`summary.json` of `flowmbd-tire steady`).
#[derive(Debug, Serialize)]
pub struct SteadySummary {
    /// Speed \[km/h\].
    pub speed_kmh: f64,
    /// Preload \[N\].
    pub load_n: f64,
    /// Friction coefficient μ \[-\].
    pub friction: f64,
    /// Cornering stiffness `dF_y/dα` at α = 0 \[N/rad\] (`null` without a slip angle).
    pub cornering_stiffness_n_per_rad: Option<f64>,
    /// Lateral relaxation length σ_α at the smallest slip angle \[m\]
    /// ([`SteadyResult::relaxation_length`]; `null` without a slip angle).
    pub relaxation_length_m: Option<f64>,
    /// Longitudinal slip stiffness `dF_x/dκ` at κ = 0 \[N\] ([`SteadyResult::slip_stiffness`];
    /// `null` without a torque point).
    pub slip_stiffness_n: Option<f64>,
    /// Slip angles \[deg\].
    pub slip_angle_deg: Vec<f64>,
    /// Side force `F_y(α)` \[N\].
    pub fy_n: Vec<f64>,
    /// Aligning moment `M_z(α)` \[N·m\].
    pub mz_n_m: Vec<f64>,
    /// Vertical force `F_z` at each slip angle \[N\].
    pub fz_n: Vec<f64>,
    /// Pneumatic trail `−M_z/F_y` at each slip angle \[m\].
    pub pneumatic_trail_m: Vec<f64>,
    /// `|F_y|/(μ F_z)` at each slip angle \[-\] of the contact forces
    /// ([`SteadyPoint::utilisation`]: at most 1 by Coulomb's law).
    pub fy_over_mu_fz: Vec<f64>,
    /// Drive torques \[N·m\].
    pub drive_torque_n_m: Vec<f64>,
    /// Longitudinal slip κ at each torque \[-\].
    pub kappa: Vec<f64>,
    /// Longitudinal force `F_x(κ)` \[N\].
    pub fx_n: Vec<f64>,
    /// `|F_x|/(μ F_z)` at each torque \[-\] of the contact forces
    /// ([`SteadyPoint::utilisation`]: at most 1 by Coulomb's law).
    pub fx_over_mu_fz: Vec<f64>,
    /// Prescribed longitudinal slips κ of the prescribed-spin sweep \[-\] (measured from the
    /// settled spin rate: equal to `slip_ratios` to the settling).
    pub prescribed_kappa: Vec<f64>,
    /// Longitudinal force `F_x(κ)` at the prescribed slips \[N\].
    pub prescribed_fx_n: Vec<f64>,
    /// `F_x/(μ F_z)` at the prescribed slips \[-\] of the contact forces, signed as `F_x`
    /// ([`SteadyPoint::utilisation`]: within ±1 by Coulomb's law).
    pub prescribed_fx_over_mu_fz: Vec<f64>,
    /// Reaction torque that holds the prescribed spin \[N·m\].
    pub prescribed_spin_torque_n_m: Vec<f64>,
    /// Free-rolling point: `F_x` (rolling resistance) \[N\], `F_z` \[N\], spin rate `Ω₀`
    /// \[rad/s\] and effective rolling radius `R_e = V_x/Ω₀` \[m\].
    pub free_rolling_fx_n: f64,
    /// `F_z` of the free-rolling point \[N\].
    pub free_rolling_fz_n: f64,
    /// `Ω₀` \[rad/s\].
    pub free_rolling_spin_rad_per_s: f64,
    /// `R_e = V_x/Ω₀` \[m\].
    pub effective_rolling_radius_m: f64,
    /// Every point in full.
    pub points: Vec<SteadyPoint>,
    /// Camber angles \[deg\].
    pub camber_deg: Vec<f64>,
    /// Camber thrust `F_y(γ)` \[N\] (W-axis: in the road plane).
    pub fy_camber_n: Vec<f64>,
    /// Vertical force `F_z` at each camber angle \[N\] (W-axis: along the road normal).
    pub fz_camber_n: Vec<f64>,
    /// Overturning moment `M_x(γ)` about the wheel centre \[N·m\].
    pub mx_camber_n_m: Vec<f64>,
    /// Aligning moment `M_z(γ)` \[N·m\] (W-axis: about the road normal).
    pub mz_camber_n_m: Vec<f64>,
    /// Camber stiffness `dF_y/dγ` at γ = 0 \[N/rad\] (`null` without a camber angle).
    pub camber_stiffness_n_per_rad: Option<f64>,
    /// Share of a contact moment about the axle that the reduced tire's rim moment carries
    /// \[-\] ([`rim_moment_transfer`]; 1 for a rotation-invariant stiffness).
    pub rim_moment_transfer: f64,
    /// Torque balance of the wheel at the torque and prescribed-spin points, in their order
    /// (torques, then slips) \[N·m\]: `spin_torque + M_y` ([`SteadyPoint::torque_residual_n_m`]).
    pub torque_residual_n_m: Vec<f64>,
    /// The same relative to the contact moment, `(spin_torque + M_y)/|M_y|` \[-\] (`null`
    /// where `|M_y|` is below 1e-6 of the load times 1 m); about `rim_moment_transfer − 1`
    /// ([`rim_moment_transfer`]).
    pub torque_residual_rel: Vec<Option<f64>>,
    /// Model stepped at the slip-angle points.
    pub symmetry: String,
    /// Model stepped at the camber points (empty without them).
    pub camber_symmetry: String,
    /// Magic Formula fit of the points ([`crate::magic_formula`]; the app writes its `.tir`,
    /// [`crate::tir`]); `None` when the points do not allow one (the reason in
    /// `magic_formula_note`).
    pub magic_formula: Option<crate::magic_formula::MfSummary>,
    /// Why there is no fit (empty when there is one).
    pub magic_formula_note: String,
    /// What the numbers mean.
    pub meaning: String,
}

/// The steady study's "what the numbers mean" paragraph.
pub const STEADY_MEANING: &str = "Steady-state characteristics of the reduced tire rolling on \
    a flat road at speed_kmh under the preload load_n (issue 38): each point starts from free \
    rolling, applies its slip angle (the road moving at tan(alpha) = -V_y/|V_x| to the wheel \
    plane, Pacejka) or drive torque, rolls for point_time and is averaged over average_time. \
    Forces and moments are in the ISO 8855 wheel frame (x forward, y left, z up; moments about \
    the wheel centre, those of the contact forces). fy_n(alpha) and mz_n_m(alpha) are the side \
    force and aligning moment, cornering_stiffness_n_per_rad = dFy/dalpha at 0, \
    pneumatic_trail_m = -Mz/Fy, fy_over_mu_fz and fx_over_mu_fz <= 1 (Coulomb's law; of the \
    contact forces, whose sums the spindle forces differ from by the tire's inertia over the \
    window), relaxation_length_m = the distance rolled after the step to the smallest slip \
    angle until Fy reaches 1 - 1/e of its settled value (Pacejka 7.2); fx_n(kappa) is the \
    longitudinal force at the drive torques with kappa = Omega/Omega0 - 1 against the \
    free-rolling spin; prescribed_fx_n(prescribed_kappa) is F_x with the spin rate held at \
    (1 + kappa) Omega0 (slip_ratios), through and beyond the peak, and \
    prescribed_spin_torque_n_m the reaction torque that holds it; slip_stiffness_n = \
    dFx/dkappa at 0 (of the prescribed points when there are any, else of the torque points). \
    fy_camber_n, mx_camber_n_m and mz_camber_n_m are the loads at the camber angles camber_deg \
    (ISO 8855 inclination: positive when the top of the wheel leans to the right; the camber \
    thrust points to the side the wheel leans to, Fy < 0 for gamma > 0), given in the W-axis \
    orientation (z along the road normal, y in the road plane; moments about the wheel centre), \
    camber_stiffness_n_per_rad = dFy/dgamma at 0. \
    torque_residual_n_m (torque points, then prescribed points) is the wheel's torque balance \
    spin torque + M_y, zero in a steady state of a consistent model; here it is about \
    (rim_moment_transfer - 1)|M_y| (torque_residual_rel): the rim moment of the reduced tire \
    (Ribaric 7.2) carries only rim_moment_transfer of a contact force's moment about the axle, \
    because the generated tire's inflation prestress stiffness (without the pressure load's \
    own stiffness) is not invariant under a rigid rotation (1 without inflation pressure). \
    Convergence: on the generated truck tire the small-slip values are converged in the \
    circumferential mesh (192 to 480 divisions: cornering stiffness within 3.1 %, relaxation \
    length within 2 %; the pneumatic trail, a moment arm of a few node spacings, within 6 mm) \
    and in the time step (0.2 to 0.025 ms: Fy within 1.3e-5) (BENCHMARKS.md, 'Steady \
    characteristics: convergence in contact nodes').";

/// The summary of a steady result.
pub fn steady_summary(cfg: &SteadyStudyConfig, r: &SteadyResult) -> SteadySummary {
    let (magic_formula, magic_formula_note) =
        match crate::magic_formula::fit_steady(r, cfg.rig.load) {
            Ok(fit) => (
                Some(crate::magic_formula::MfSummary::new(&fit, r, None)),
                String::new(),
            ),
            Err(e) => (None, e.to_string()),
        };
    let mu = cfg.rig.rolling.friction;
    let v = cfg.rig.speed_kmh / 3.6;
    let f = &r.free_rolling;
    SteadySummary {
        speed_kmh: cfg.rig.speed_kmh,
        load_n: cfg.rig.load,
        friction: mu,
        cornering_stiffness_n_per_rad: r.cornering_stiffness(),
        relaxation_length_m: r.relaxation_length(),
        slip_stiffness_n: r.slip_stiffness(),
        slip_angle_deg: r.slip.iter().map(|p| p.slip_angle_deg).collect(),
        fy_n: r.slip.iter().map(|p| p.loads.fy).collect(),
        mz_n_m: r.slip.iter().map(|p| p.loads.mz).collect(),
        fz_n: r.slip.iter().map(|p| p.loads.fz).collect(),
        pneumatic_trail_m: r.pneumatic_trail(),
        fy_over_mu_fz: r.slip.iter().map(|p| p.utilisation[1]).collect(),
        fx_over_mu_fz: r.torque.iter().map(|p| p.utilisation[0]).collect(),
        drive_torque_n_m: r.torque.iter().map(|p| p.drive_torque_n_m).collect(),
        kappa: r.torque.iter().map(|p| p.kappa).collect(),
        fx_n: r.torque.iter().map(|p| p.loads.fx).collect(),
        prescribed_kappa: r.prescribed.iter().map(|p| p.kappa).collect(),
        prescribed_fx_n: r.prescribed.iter().map(|p| p.loads.fx).collect(),
        prescribed_fx_over_mu_fz: r
            .prescribed
            .iter()
            .map(|p| p.utilisation[0].copysign(p.loads.fx))
            .collect(),
        prescribed_spin_torque_n_m: r.prescribed.iter().map(|p| p.spin_torque_n_m).collect(),
        free_rolling_fx_n: f.loads.fx,
        free_rolling_fz_n: f.loads.fz,
        free_rolling_spin_rad_per_s: f.spin_rad_per_s,
        effective_rolling_radius_m: v / f.spin_rad_per_s,
        camber_deg: r.camber.iter().map(|p| p.camber_deg).collect(),
        fy_camber_n: r.camber.iter().map(|p| p.loads.fy).collect(),
        fz_camber_n: r.camber.iter().map(|p| p.loads.fz).collect(),
        mx_camber_n_m: r.camber.iter().map(|p| p.loads.mx).collect(),
        mz_camber_n_m: r.camber.iter().map(|p| p.loads.mz).collect(),
        camber_stiffness_n_per_rad: r.camber_stiffness(),
        points: std::iter::once(*f)
            .chain(r.slip.iter().copied())
            .chain(r.torque.iter().copied())
            .chain(r.prescribed.iter().copied())
            .chain(r.camber.iter().copied())
            .collect(),
        rim_moment_transfer: r.rim_moment_transfer,
        torque_residual_n_m: r
            .torque
            .iter()
            .chain(&r.prescribed)
            .map(|p| p.torque_residual_n_m)
            .collect(),
        torque_residual_rel: r
            .torque
            .iter()
            .chain(&r.prescribed)
            .map(|p| {
                (p.loads.my.abs() > 1e-6 * cfg.rig.load)
                    .then(|| p.torque_residual_n_m / p.loads.my.abs())
            })
            .collect(),
        symmetry: r.symmetry.clone(),
        camber_symmetry: r.camber_symmetry.clone(),
        magic_formula,
        magic_formula_note,
        meaning: STEADY_MEANING.to_string(),
    }
}

/// Columns of the steady study's point table (`points.csv`): slip angle \[deg\], drive torque
/// \[N·m\], torque on the wheel (drive or reaction of a prescribed spin) \[N·m\], κ \[-\],
/// spin \[rad/s\], the six loads (ISO 8855 wheel frame; at a camber angle the W-axis
/// orientation, z along the road normal) \[N\], \[N·m\], the spread over the averaging window
/// \[N\], the camber angle \[deg\].
pub const STEADY_COLUMNS: [&str; 13] = [
    "slip_angle_deg",
    "drive_torque_N_m",
    "spin_torque_N_m",
    "kappa_ratio",
    "spin_rad_per_s",
    "fx_N",
    "fy_N",
    "fz_N",
    "mx_N_m",
    "my_N_m",
    "mz_N_m",
    "spread_N",
    "camber_deg",
];

/// The [`STEADY_COLUMNS`] row of a point.
pub fn steady_row(p: &SteadyPoint) -> [f64; 13] {
    let l = &p.loads;
    [
        p.slip_angle_deg,
        p.drive_torque_n_m,
        p.spin_torque_n_m,
        p.kappa,
        p.spin_rad_per_s,
        l.fx,
        l.fy,
        l.fz,
        l.mx,
        l.my,
        l.mz,
        p.spread_n,
        p.camber_deg,
    ]
}
