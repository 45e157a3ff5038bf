//! Steady-state force and moment characteristics of the rolling tire on a flat road (issue 38,
//! items 1 and 5): the side force `F_y(α)` and aligning moment `M_z(α)` over a sweep of slip
//! angles, the longitudinal force `F_x(κ)` over a sweep of drive/brake torques and the camber
//! thrust `F_y(γ)` with `M_x(γ)`, `M_z(γ)` over a sweep of camber angles, each point settled on
//! the same rig and time stepper as the cleat test ([`crate::rig::run_cleat`] without a cleat,
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
use crate::rig::{MAX_RIG_STEPS, RigConfig, run_cleat};
use crate::rolling::WheelLoads;
use crate::source::TireSource;
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Most points of one steady sweep (slip angles plus torques plus the free-rolling point).
pub const MAX_STEADY_POINTS: usize = 1000;

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
        Self {
            tire: TireSource::default(),
            rig,
            slip_angles_deg: vec![-0.2, 0.2, 1.0, 4.0],
            drive_torques_n_m: vec![-1000.0, 1000.0],
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
            + 1;
        check::size("slip_angles_deg", n, 1, MAX_STEADY_POINTS)?;
        for (i, a) in self.slip_angles_deg.iter().enumerate() {
            let max = crate::rig::MAX_SLIP_ANGLE_DEG;
            check::within(&format!("slip_angles_deg[{i}]"), *a, -max, max, "deg")?;
        }
        for (i, t) in self.drive_torques_n_m.iter().enumerate() {
            check::finite(&format!("drive_torques_n_m[{i}]"), *t)?;
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
    /// Drive torque \[N·m\].
    pub drive_torque_n_m: f64,
    /// Camber angle γ \[deg\].
    pub camber_deg: f64,
    /// Longitudinal slip `κ = Ω/Ω₀ − 1` against the free-rolling spin rate `Ω₀` \[-\].
    pub kappa: f64,
    /// Mean spin rate Ω \[rad/s\].
    pub spin_rad_per_s: f64,
    /// Mean loads over the last `average_time` (ISO 8855 wheel frame; with camber the W-axis
    /// orientation, [`WheelLoads`]).
    pub loads: WheelLoads,
    /// Largest minus smallest `F_y` over the averaging window \[N\] (how settled the point is;
    /// likewise for the torque points' `F_x`).
    pub spread_n: f64,
    /// Sum of the normal contact forces at the end \[N\].
    pub normal_sum_n: f64,
    /// Contact nodes in contact at the end.
    pub active_nodes: usize,
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
    /// The camber points in the order of `camber_angles_deg`.
    pub camber: Vec<SteadyPoint>,
    /// Model stepped at the slip-angle points (full model when α ≠ 0).
    pub symmetry: String,
    /// Model stepped at the camber points (full model when γ ≠ 0; empty without them).
    pub camber_symmetry: String,
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

impl SteadyResult {
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

/// The wheel inputs of one point: slip angle \[deg\], drive torque \[N·m\], camber \[deg\].
#[derive(Debug, Clone, Copy)]
struct PointInputs {
    alpha_deg: f64,
    torque: f64,
    camber_deg: f64,
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
    } = inp;
    let mut rig = cfg.rig.clone();
    rig.settle_time = cfg.point_time;
    rig.record_time = 0.0;
    rig.wheel.slip_angle_deg = alpha_deg;
    rig.wheel.drive_torque = torque;
    rig.wheel.camber_deg = camber_deg;
    // (the rig names its fields relative to itself; the study's root has them under `rig.`)
    let r = run_cleat(red, &rig, progress).map_err(|e| match e {
        TireError::Invalid { item, reason } => TireError::Invalid {
            item: format!("rig.{item}"),
            reason,
        },
        other => other,
    })?;
    let t_end = r.samples.last().map_or(0.0, |s| s.t);
    let w: Vec<_> = r
        .samples
        .iter()
        .filter(|s| s.t > t_end - cfg.average_time)
        .collect();
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
    let watch = |s: &crate::rig::Sample| if torque != 0.0 { s.fx } else { s.fz };
    let hi = w.iter().map(|s| watch(s)).fold(f64::MIN, f64::max);
    let lo = w.iter().map(|s| watch(s)).fold(f64::MAX, f64::min);
    let last = r.samples.last();
    Ok((
        SteadyPoint {
            slip_angle_deg: alpha_deg,
            drive_torque_n_m: torque,
            camber_deg,
            kappa: omega0.map_or(0.0, |o| spin / o - 1.0),
            spin_rad_per_s: spin,
            loads,
            spread_n: if w.is_empty() { 0.0 } else { hi - lo },
            normal_sum_n: last.map_or(0.0, |s| s.normal_sum),
            active_nodes: last.map_or(0, |s| s.active),
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
    let total =
        (1 + cfg.slip_angles_deg.len() + cfg.drive_torques_n_m.len() + cfg.camber_angles_deg.len())
            as f64;
    let mut k = 0.0;
    let at = |alpha_deg, torque, camber_deg| PointInputs {
        alpha_deg,
        torque,
        camber_deg,
    };
    let (free, _) = run_point(red, cfg, at(0.0, 0.0, 0.0), None, &mut |f| {
        progress(f / total)
    })?;
    k += 1.0;
    let omega0 = free.spin_rad_per_s;
    let mut slip = Vec::with_capacity(cfg.slip_angles_deg.len());
    let mut symmetry = String::new();
    for &a in &cfg.slip_angles_deg {
        let (p, s) = run_point(red, cfg, at(a, 0.0, 0.0), Some(omega0), &mut |f| {
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
        let (p, _) = run_point(red, cfg, at(0.0, t, 0.0), Some(omega0), &mut |f| {
            progress((k + f) / total)
        })?;
        k += 1.0;
        torque.push(p);
    }
    let mut camber = Vec::with_capacity(cfg.camber_angles_deg.len());
    let mut camber_symmetry = String::new();
    for &g in &cfg.camber_angles_deg {
        let (p, s) = run_point(red, cfg, at(0.0, 0.0, g), Some(omega0), &mut |f| {
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
        camber,
        symmetry,
        camber_symmetry,
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
    /// `|F_y|/(μ F_z)` at each slip angle \[-\] (at most 1 by Coulomb's law).
    pub fy_over_mu_fz: Vec<f64>,
    /// Drive torques \[N·m\].
    pub drive_torque_n_m: Vec<f64>,
    /// Longitudinal slip κ at each torque \[-\].
    pub kappa: Vec<f64>,
    /// Longitudinal force `F_x(κ)` \[N\].
    pub fx_n: Vec<f64>,
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
    pneumatic_trail_m = -Mz/Fy, fy_over_mu_fz <= 1 (Coulomb); fx_n(kappa) is the longitudinal \
    force at the drive torques with kappa = Omega/Omega0 - 1 against the free-rolling spin. \
    fy_camber_n, mx_camber_n_m and mz_camber_n_m are the loads at the camber angles camber_deg \
    (ISO 8855 inclination: positive when the top of the wheel leans to the right; the camber \
    thrust points to the side the wheel leans to, Fy < 0 for gamma > 0), given in the W-axis \
    orientation (z along the road normal, y in the road plane; moments about the wheel centre), \
    camber_stiffness_n_per_rad = dFy/dgamma at 0.";

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
        slip_angle_deg: r.slip.iter().map(|p| p.slip_angle_deg).collect(),
        fy_n: r.slip.iter().map(|p| p.loads.fy).collect(),
        mz_n_m: r.slip.iter().map(|p| p.loads.mz).collect(),
        fz_n: r.slip.iter().map(|p| p.loads.fz).collect(),
        pneumatic_trail_m: r.pneumatic_trail(),
        fy_over_mu_fz: r
            .slip
            .iter()
            .map(|p| p.loads.fy.abs() / (mu * p.loads.fz))
            .collect(),
        drive_torque_n_m: r.torque.iter().map(|p| p.drive_torque_n_m).collect(),
        kappa: r.torque.iter().map(|p| p.kappa).collect(),
        fx_n: r.torque.iter().map(|p| p.loads.fx).collect(),
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
            .chain(r.camber.iter().copied())
            .collect(),
        symmetry: r.symmetry.clone(),
        camber_symmetry: r.camber_symmetry.clone(),
        magic_formula,
        magic_formula_note,
        meaning: STEADY_MEANING.to_string(),
    }
}

/// Columns of the steady study's point table (`points.csv`): slip angle \[deg\], drive torque
/// \[N·m\], κ \[-\], spin \[rad/s\], the six loads (ISO 8855 wheel frame; at a camber angle
/// the W-axis orientation, z along the road normal) \[N\], \[N·m\], the spread over the
/// averaging window \[N\], the camber angle \[deg\].
pub const STEADY_COLUMNS: [&str; 12] = [
    "slip_angle_deg",
    "drive_torque_N_m",
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
pub fn steady_row(p: &SteadyPoint) -> [f64; 12] {
    let l = &p.loads;
    [
        p.slip_angle_deg,
        p.drive_torque_n_m,
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
