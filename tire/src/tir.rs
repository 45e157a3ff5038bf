//! Writer of a Magic Formula 6.1 tyre property file (`.tir`, the format read by Adams, MF-Tyre
//! and MFeval) from a single-load fit ([`crate::magic_formula::MfFit`]).
//!
//! The mapping of the fitted `B, C, D, E, S_h, S_v` onto the MF 6.1 coefficients follows the
//! pure-slip equations of Pacejka, *Tire and Vehicle Dynamics*, 3rd ed., §4.3.2, evaluated at
//! `F_z = FNOMIN` (so `df_z = 0`, eq. 4.E2a), zero camber (`γ* = 0`), nominal pressure
//! (`dp_i = 0`, eq. 4.E2b), no turn slip (all `ζ_i = 1`) and all scaling factors `λ = 1`:
//!
//! Sign convention: a `.tir` is read in the TYDEX / ISO W-axis system, in which the slip angle
//! is `tan α_W = V_y/|V_x|` and a free tire's side force falls with it (`PKY1 < 0` in every
//! MF-Tyre parameter set). The fit is in Pacejka's slip angle of [`crate::steady`],
//! `tan α = −V_y/|V_x|` (forces in the same ISO 8855 axes), so `α_W = −α` and the file holds the
//! mirrored curves `F_yW(x) = F_y(−x)`, `M_zW(x) = M_z(−x)`: with the sine form odd in
//! `B(x + S_h)` and the trail's cosine even, that is `B_y = −B`, `S_Hy = −S_h` and `S_Ht = −S_ht`,
//! the rest unchanged. The longitudinal slip `κ` has the same sign in both.
//!
//! Lateral (eqs. 4.E19–4.E30): `C_y = PCY1`; `D_y = μ_y F_z` with `μ_y = PDY1` (4.E23) so
//! `PDY1 = D/F_z0`; `E_y = PEY1` (4.E24); `K_yα = PKY1 F_z0 sin(PKY4 atan(F_z/(PKY2 F_z0)))`
//! (4.E25), with `PKY2 = 1`, `PKY4 = 2` this is `PKY1 F_z0`, so `PKY1 = −B C D/F_z0` and
//! `B_y = K_yα/(C_y D_y)` (4.E26) returns `−B`; `S_Hy = PHY1` (4.E27) `= −S_h`;
//! `S_Vy = F_z PVY1` (4.E29) so `PVY1 = S_v/F_z0`.
//!
//! Aligning (eqs. 4.E31–4.E49): `t_0 = D_t cos(C_t atan(B_t α_t − E_t(B_t α_t −
//! atan(B_t α_t)))) cos'α` (4.E33) with `B_t = QBZ1` (4.E40; the cosine is even in `B_t`, so
//! `QBZ1 = |B_t|`), `C_t = QCZ1` (4.E41), `D_t = F_z (R_0/F_z0) QDZ1` (4.E42) so
//! `QDZ1 = D_t/R_0`, `E_t = QEZ1` (4.E44), `S_Ht = QHZ1` (4.E35) `= −S_ht`; the residual moment
//! `M_zr` is zero (`QDZ6..QDZ9 = 0`, `QBZ9 = QBZ10 = 0`).
//!
//! Longitudinal (eqs. 4.E9–4.E18): `C_x = PCX1`; `μ_x = PDX1` so `PDX1 = D/F_z0`;
//! `E_x = PEX1`; `K_xκ = F_z PKX1` (4.E15) so `PKX1 = B C D/F_z0`; `S_Hx = PHX1`;
//! `S_Vx = F_z PVX1` so `PVX1 = S_v/F_z0`.
//!
//! All load-, camber-, pressure- and combined-slip coefficients are written as zero, all
//! scaling factors `LMU..` as one: the file reproduces the fit only at `F_z = FNOMIN`, zero
//! camber, nominal pressure and pure slip.

use crate::magic_formula::{FitError, MfFit};
use crate::reduced::ReducedTire;
use crate::steady::SteadyStudyConfig;
use std::fmt::Write as _;

/// Tyre data of the `.tir` besides the fitted coefficients (SI units, as in `[UNITS]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TirTyre {
    /// Unloaded radius `R_0` \[m\] (`UNLOADED_RADIUS`).
    pub unloaded_radius: f64,
    /// Nominal section width \[m\] (`WIDTH`).
    pub width: f64,
    /// Reference speed \[m/s\] (`LONGVL`), the study's speed.
    pub speed: f64,
    /// Nominal inflation pressure \[Pa\] (`NOMPRES`, `INFLPRES`); `None` writes 1e5 Pa,
    /// noted in the file (no written coefficient depends on the pressure: `dp_i = 0`).
    pub pressure: Option<f64>,
    /// Vertical stiffness \[N/m\] (`VERTICAL_STIFFNESS`, used by readers for the loaded
    /// radius only, not by the pure-slip forces); `None` writes 0, noted in the file.
    pub vertical_stiffness: Option<f64>,
}

/// The MF 6.1 coefficients of the fit ([module docs](self)), `(section, name, value)`:
/// only the non-zero ones of the coefficient sections.
pub fn mf61_coefficients(fit: &MfFit, r0: f64) -> Vec<(&'static str, &'static str, f64)> {
    let fz0 = fit.fz_n;
    let y = &fit.lateral.fy;
    let t = &fit.lateral.trail;
    let mut v = vec![
        ("LATERAL_COEFFICIENTS", "PCY1", y.c),
        ("LATERAL_COEFFICIENTS", "PDY1", y.d / fz0),
        ("LATERAL_COEFFICIENTS", "PEY1", y.e),
        // W-axis slip angle α_W = −α (module docs): B_y = −B, S_Hy = −S_h
        ("LATERAL_COEFFICIENTS", "PKY1", -y.stiffness() / fz0),
        ("LATERAL_COEFFICIENTS", "PKY2", 1.0),
        ("LATERAL_COEFFICIENTS", "PKY4", 2.0),
        ("LATERAL_COEFFICIENTS", "PHY1", -y.sh),
        ("LATERAL_COEFFICIENTS", "PVY1", y.sv / fz0),
        ("ALIGNING_COEFFICIENTS", "QBZ1", t.b.abs()),
        ("ALIGNING_COEFFICIENTS", "QCZ1", t.c),
        ("ALIGNING_COEFFICIENTS", "QDZ1", t.d / r0),
        ("ALIGNING_COEFFICIENTS", "QEZ1", t.e),
        ("ALIGNING_COEFFICIENTS", "QHZ1", -t.sh),
    ];
    if let Some(l) = &fit.longitudinal {
        let x = &l.fx;
        v.extend([
            ("LONGITUDINAL_COEFFICIENTS", "PCX1", x.c),
            ("LONGITUDINAL_COEFFICIENTS", "PDX1", x.d / fz0),
            ("LONGITUDINAL_COEFFICIENTS", "PEX1", x.e),
            ("LONGITUDINAL_COEFFICIENTS", "PKX1", x.stiffness() / fz0),
            ("LONGITUDINAL_COEFFICIENTS", "PHX1", x.sh),
            ("LONGITUDINAL_COEFFICIENTS", "PVX1", x.sv / fz0),
        ]);
    }
    v
}

/// Coefficient names of each section (MF 6.1), written as zero unless fitted.
const SECTIONS: [(&str, &[&str]); 4] = [
    (
        "LONGITUDINAL_COEFFICIENTS",
        &[
            "PCX1", "PDX1", "PDX2", "PDX3", "PEX1", "PEX2", "PEX3", "PEX4", "PKX1", "PKX2", "PKX3",
            "PHX1", "PHX2", "PVX1", "PVX2", "PPX1", "PPX2", "PPX3", "PPX4", "RBX1", "RBX2", "RBX3",
            "RCX1", "REX1", "REX2", "RHX1",
        ],
    ),
    (
        "LATERAL_COEFFICIENTS",
        &[
            "PCY1", "PDY1", "PDY2", "PDY3", "PEY1", "PEY2", "PEY3", "PEY4", "PEY5", "PKY1", "PKY2",
            "PKY3", "PKY4", "PKY5", "PKY6", "PKY7", "PHY1", "PHY2", "PVY1", "PVY2", "PVY3", "PVY4",
            "PPY1", "PPY2", "PPY3", "PPY4", "PPY5", "RBY1", "RBY2", "RBY3", "RBY4", "RCY1", "REY1",
            "REY2", "RHY1", "RHY2", "RVY1", "RVY2", "RVY3", "RVY4", "RVY5", "RVY6",
        ],
    ),
    (
        "ALIGNING_COEFFICIENTS",
        &[
            "QBZ1", "QBZ2", "QBZ3", "QBZ4", "QBZ5", "QBZ9", "QBZ10", "QCZ1", "QDZ1", "QDZ2",
            "QDZ3", "QDZ4", "QDZ6", "QDZ7", "QDZ8", "QDZ9", "QDZ10", "QDZ11", "QEZ1", "QEZ2",
            "QEZ3", "QEZ4", "QEZ5", "QHZ1", "QHZ2", "QHZ3", "QHZ4", "PPZ1", "PPZ2", "SSZ1", "SSZ2",
            "SSZ3", "SSZ4",
        ],
    ),
    (
        "OVERTURNING_COEFFICIENTS",
        &[
            "QSX1", "QSX2", "QSX3", "QSX4", "QSX5", "QSX6", "QSX7", "QSX8", "QSX9", "QSX10",
            "QSX11", "PPMX1",
        ],
    ),
];

/// Scaling factors of MF 6.1, all written as one.
const SCALING: [&str; 28] = [
    "LFZO", "LCX", "LMUX", "LEX", "LKX", "LHX", "LVX", "LCY", "LMUY", "LEY", "LKY", "LKYC", "LKZC",
    "LHY", "LVY", "LTR", "LRES", "LXAL", "LYKA", "LVYKA", "LS", "LMX", "LVMX", "LMY", "LMP",
    "LSGKP", "LSGAL", "LMUV",
];

fn error_line(s: &mut String, name: &str, e: &FitError, unit: &str) {
    let _ = writeln!(
        s,
        "$ {name}: {} points, {} coefficients fitted; RMS error {:.4e} {unit} ({:.3e} of the \
         peak {:.4e} {unit}), max error {:.4e} {unit} ({:.3e} of the peak)",
        e.points, e.free_coefficients, e.rms, e.rms_fraction, e.peak, e.max, e.max_fraction
    );
}

/// The `.tir` text (MF 6.1, `FITTYP = 61`) of a single-load fit ([module docs](self) give the
/// mapping and its equations); `source` names the data in the comment header.
pub fn write_tir(fit: &MfFit, tyre: &TirTyre, source: &str) -> String {
    let fitted = mf61_coefficients(fit, tyre.unloaded_radius);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "[MDI_HEADER]\nFILE_TYPE                = 'tir'\nFILE_VERSION             = 3.0\n\
         FILE_FORMAT              = 'ASCII'"
    );
    s.push_str(
        "$ Magic Formula 6.1 (Pacejka, Tire and Vehicle Dynamics, 3rd ed., sec. 4.3.2) fitted by\n\
         $ flowmbd (tire::magic_formula, tire::tir) to a steady-state simulation at ONE load.\n",
    );
    let _ = writeln!(s, "$ Data: {source}");
    let _ = writeln!(
        s,
        "$ Valid only at Fz = FNOMIN = {:.6e} N, zero camber, NOMPRES, pure slip.",
        fit.fz_n
    );
    s.push_str(
        "$ Fitted: PCY1 PDY1 PEY1 PKY1 PHY1 PVY1 (PKY2 = 1, PKY4 = 2 so Kya = PKY1*FNOMIN),\n\
         $ QBZ1 QCZ1 QDZ1 QEZ1 QHZ1 (residual moment Mzr = 0), and, when present,\n\
         $ PCX1 PDX1 PEX1 PKX1 PHX1 PVX1. Coefficients freed in this order until one fewer\n\
         $ than the points: B, D, Sv, C, E, Sh (trail: Dt, Bt, Ct, Et, Sht); the rest held.\n\
         $ All load (dfz), camber, pressure, combined-slip, overturning and rolling-resistance\n\
         $ coefficients are ZERO; all scaling factors L.. are 1.\n",
    );
    error_line(&mut s, "Fy(alpha)", &fit.lateral.fy_error, "N");
    error_line(&mut s, "Mz(alpha)", &fit.lateral.mz_error, "N m");
    match &fit.longitudinal {
        Some(l) => error_line(&mut s, "Fx(kappa)", &l.fx_error, "N"),
        None => s.push_str("$ Fx(kappa): not fitted (too few torque points); zero\n"),
    }
    for w in crate::magic_formula::fit_warnings(fit) {
        let _ = writeln!(s, "$ WARNING: {w}");
    }
    let kv = |s: &mut String, k: &str, v: f64| {
        let _ = writeln!(s, "{k:<25}= {v:.15e}");
    };
    s.push_str(
        "[UNITS]\nLENGTH                   = 'meter'\nFORCE                    = 'newton'\n\
         ANGLE                    = 'radians'\nMASS                     = 'kg'\n\
         TIME                     = 'second'\n",
    );
    s.push_str("[MODEL]\nFITTYP                   = 61\nTYRESIDE                 = 'LEFT'\n");
    kv(&mut s, "LONGVL", tyre.speed);
    kv(&mut s, "VXLOW", 1.0);
    s.push_str("[DIMENSION]\n");
    kv(&mut s, "UNLOADED_RADIUS", tyre.unloaded_radius);
    kv(&mut s, "WIDTH", tyre.width);
    kv(&mut s, "RIM_RADIUS", 0.0);
    kv(&mut s, "RIM_WIDTH", 0.0);
    s.push_str("[OPERATING_CONDITIONS]\n");
    if tyre.pressure.is_none() {
        s.push_str(
            "$ pressure not known to the fit: placeholder 1e5 Pa (no coefficient uses it)\n",
        );
    }
    kv(&mut s, "INFLPRES", tyre.pressure.unwrap_or(1e5));
    kv(&mut s, "NOMPRES", tyre.pressure.unwrap_or(1e5));
    s.push_str("[VERTICAL]\n");
    kv(&mut s, "FNOMIN", fit.fz_n);
    if tyre.vertical_stiffness.is_none() {
        s.push_str(
            "$ vertical stiffness not known to the fit: 0 (not used by the pure-slip forces)\n",
        );
    }
    kv(
        &mut s,
        "VERTICAL_STIFFNESS",
        tyre.vertical_stiffness.unwrap_or(0.0),
    );
    kv(&mut s, "VERTICAL_DAMPING", 0.0);
    s.push_str("[VERTICAL_FORCE_RANGE]\n");
    kv(&mut s, "FZMIN", 0.0);
    kv(&mut s, "FZMAX", 10.0 * fit.fz_n);
    s.push_str("[SLIP_RANGE]\n");
    kv(&mut s, "KPUMIN", -1.5);
    kv(&mut s, "KPUMAX", 1.5);
    s.push_str("[SLIP_ANGLE_RANGE]\n");
    kv(&mut s, "ALPMIN", -1.5);
    kv(&mut s, "ALPMAX", 1.5);
    s.push_str("[INCLINATION_ANGLE_RANGE]\n");
    kv(&mut s, "CAMMIN", -1.0);
    kv(&mut s, "CAMMAX", 1.0);
    s.push_str("[SCALING_COEFFICIENTS]\n");
    for k in SCALING {
        kv(&mut s, k, 1.0);
    }
    for (sec, names) in SECTIONS {
        let _ = writeln!(s, "[{sec}]");
        for n in names {
            let v = fitted
                .iter()
                .find(|(fs, fn_, _)| *fs == sec && fn_ == n)
                .map_or(0.0, |f| f.2);
            kv(&mut s, n, v);
        }
    }
    s
}

/// Parse `NAME = value` lines of a `.tir` text into `(section, name, value)` (numeric values
/// only; comments after `$` dropped) — the reader the tests use to check the written file.
pub fn parse_tir(text: &str) -> Vec<(String, String, f64)> {
    let mut sec = String::new();
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.split('$').next().unwrap_or("").trim();
        if let Some(h) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            sec = h.to_string();
        } else if let Some((k, v)) = line.split_once('=')
            && let Ok(x) = v.trim().parse::<f64>()
        {
            out.push((sec.clone(), k.trim().to_string(), x));
        }
    }
    out
}

/// The `.tir` text of the fit `fit` of a steady study ([`crate::steady`]) on the reduced tire
/// `red` with the configuration `cfg` (`flowmbd-tire steady`'s `tire.tir`, the Python
/// `flowmbd.tire.steady`'s `tir_text`): [`write_tir`] with `UNLOADED_RADIUS` = the tire's
/// outer radius `R_0` \[m\], `WIDTH` = the lateral extent of its contact nodes \[m\] (the
/// tread band the road can touch), `LONGVL` = the rig's speed \[m/s\], pressure and vertical
/// stiffness not known to the fit (noted in the file), and the load, speed and friction of the
/// data in the header.
pub fn steady_tir(fit: &MfFit, red: &ReducedTire, cfg: &SteadyStudyConfig) -> String {
    let ys = red.contact_positions.iter().map(|p| p[1]);
    let width = ys.clone().fold(f64::MIN, f64::max) - ys.fold(f64::MAX, f64::min);
    let tyre = TirTyre {
        unloaded_radius: red.outer_radius,
        width,
        speed: cfg.rig.speed_kmh / 3.6,
        pressure: None,
        vertical_stiffness: None,
    };
    write_tir(
        fit,
        &tyre,
        &format!(
            "flowmbd-tire steady, load {} N, {} km/h, friction {}",
            cfg.rig.load, cfg.rig.speed_kmh, cfg.rig.rolling.friction
        ),
    )
}
