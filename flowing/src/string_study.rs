//! The travelling-string modes study of Ribaric §4.2.3: damped natural frequencies of the
//! analytical Galerkin model (4.24)–(4.29) and of the discrete flowing-material model (4.20)
//! at one axial speed. The configuration, its checks and the summary are what
//! `flowmbd-string modes` reads and writes, shared with the Python package
//! (`flowmbd.string.modes`); the model-building helpers are shared by every string study.

use crate::error::FlowError;
use crate::{
    AxialMotion, DerivativeMethod, FlowingString, GalerkinString, StringConfig, StringMesh,
};
use mbd_core::validate::{InvalidField, Validate, check};
use serde::{Deserialize, Serialize};

/// Checks the string parameters (finite and positive), naming the field `prefix.name`.
pub fn check_string(p: &StringConfig, prefix: &str) -> Result<(), InvalidField> {
    for (name, v) in [
        ("length", p.length),
        ("density", p.density),
        ("area", p.area),
        ("tension", p.tension),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(InvalidField::new(
                format!("{prefix}.{name}"),
                format!("must be a positive number, got {v}"),
            ));
        }
    }
    Ok(())
}

/// Checks that `v` is finite (and non-negative if `non_negative`).
pub fn check_number(field: &str, v: f64, non_negative: bool) -> Result<(), InvalidField> {
    if !v.is_finite() || (non_negative && v < 0.0) {
        return Err(InvalidField::new(
            field,
            format!(
                "must be a finite{} number, got {v}",
                if non_negative { " non-negative" } else { "" }
            ),
        ));
    }
    Ok(())
}

/// Most interior nodes of a string model: its mass and stiffness matrices and the modal
/// eigen problem are dense (`nodes²` entries, `O(nodes³)` work: about a second at 2000), so
/// larger counts are refused before anything is allocated (`--nodes 1e9` aborted on the
/// allocation, issue 20). Ribaric's string has 99.
pub const MAX_STRING_NODES: usize = 2000;

/// Most sine terms of the Galerkin model (4.24) (dense `2N × 2N` state matrix, as
/// [`MAX_STRING_NODES`]).
pub const MAX_GALERKIN_TERMS: usize = 2000;

/// Checks `3 ≤ nodes ≤` [`MAX_STRING_NODES`] and `1 ≤ modes ≤ nodes`.
pub fn check_nodes_modes(nodes: usize, modes: usize) -> Result<(), InvalidField> {
    if nodes < 3 {
        return Err(InvalidField::new(
            "nodes",
            format!("needs at least 3 interior nodes, got {nodes}"),
        ));
    }
    check::size("nodes", nodes, 3, MAX_STRING_NODES)?;
    if modes == 0 || modes > nodes {
        return Err(InvalidField::new(
            "modes",
            format!("must be between 1 and nodes = {nodes}, got {modes}"),
        ));
    }
    Ok(())
}

/// Checks that `duration / step` (both \[s\], positive) is at most `max` steps or samples, naming
/// `field` (the run's length is bounded before it starts).
pub fn check_steps(
    field: &str,
    duration: f64,
    step: f64,
    max: f64,
    what: &str,
) -> Result<(), InvalidField> {
    let n = duration / step;
    let max = mbd_core::validate::limits::ceiling(max);
    if n > max {
        return Err(InvalidField::new(
            field,
            format!(
                "{} s in steps of {} s is {n:.3e} {what}, more than the {max:e} a run may take{}",
                check::show(duration),
                check::show(step),
                mbd_core::validate::limits::raise_hint()
            ),
        ));
    }
    Ok(())
}

/// The string mesh of `nodes` interior nodes (Ribaric (4.1)) and its flowing-material model
/// (4.20) with `modes` modes at the constant axial speed `speed` \[m/s\].
pub fn flowing_model(
    p: StringConfig,
    nodes: usize,
    modes: usize,
    method: DerivativeMethod,
    speed: f64,
) -> Result<(StringMesh, FlowingString), FlowError> {
    let mesh = StringMesh::uniform(p, nodes)?;
    let basis = mesh.modes(modes)?;
    let sys = FlowingString::new(
        &mesh.mass_sys(),
        basis,
        &[mesh.flow_line()],
        method,
        AxialMotion::Constant { speed },
    )?;
    Ok((mesh, sys))
}

/// Eigen analysis of the Galerkin model (4.29) with `terms` sine terms at `speed` \[m/s\]:
/// (damped frequencies \[Hz\] ascending, max real part \[1/s\]).
pub fn galerkin_frequencies(
    p: StringConfig,
    speed: f64,
    terms: usize,
) -> Result<(Vec<f64>, f64), FlowError> {
    let g = GalerkinString::new(p, speed, terms)?;
    let e = g.system().state_eigen()?;
    Ok((e.damped_frequencies_hz(), e.max_real_part()))
}

/// Eigen analysis of the flowing model (4.20) frozen at `speed` \[m/s\]: (damped frequencies
/// \[Hz\] ascending, max real part \[1/s\]).
pub fn flowing_frequencies(sys: &FlowingString, speed: f64) -> Result<(Vec<f64>, f64), FlowError> {
    let e = sys.frozen(speed, 0.0).state_eigen()?;
    Ok((e.damped_frequencies_hz(), e.max_real_part()))
}

/// Configuration of the modes study (defaults: Ribaric 4.2.3 string at 20 m/s, 99 nodes,
/// 20 modes).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ModesConfig {
    /// String parameters.
    pub string: StringConfig,
    /// Axial speed \[m/s\].
    pub speed: f64,
    /// Interior FE nodes (Ribaric (4.1)).
    pub nodes: usize,
    /// Retained modes of the flowing-material model (4.20).
    pub modes: usize,
    /// Sine terms of the Galerkin model (4.24).
    pub galerkin_terms: usize,
    /// Number of frequencies reported per model.
    pub report: usize,
    /// Mode-shape derivative operator (Ribaric App. A).
    pub derivative: DerivativeMethod,
}

impl Default for ModesConfig {
    fn default() -> Self {
        Self {
            string: StringConfig::default(),
            speed: 20.0,
            nodes: 99,
            modes: 20,
            galerkin_terms: 40,
            report: 10,
            derivative: DerivativeMethod::default(),
        }
    }
}

impl Validate for ModesConfig {
    fn validate(&self) -> Result<(), InvalidField> {
        check_string(&self.string, "string")?;
        check_number("speed", self.speed, false)?;
        check_nodes_modes(self.nodes, self.modes)?;
        check::size("galerkin_terms", self.galerkin_terms, 1, MAX_GALERKIN_TERMS)?;
        if self.report == 0 {
            return Err(InvalidField::new("report", "must be at least 1"));
        }
        Ok(())
    }
}

/// A growing solution of a linear model: an eigenvalue `λ` with `Re λ > 0`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Growth {
    /// Growth rate `Re λ` \[1/s\] (the amplitude grows as `e^{rate·t}`).
    pub rate_per_s: f64,
    /// Frequency `Im λ/2π` \[Hz\] (0: divergence, a non-oscillating growth; > 0: flutter).
    pub frequency_hz: f64,
}

/// Relative deviation from the exact travelling-string frequencies above which the modes
/// study warns that its models are not converged (5 %: the 99-node mesh alone is within
/// 3.1 % of the exact 10th frequency up to v = 0.97 c with a full basis).
pub const CONVERGENCE_TOLERANCE: f64 = 0.05;

/// Summary of the modes study (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct ModesSummary {
    /// Axial speed \[m/s\].
    pub speed: f64,
    /// Critical speed `c = √(T/ρA)` \[m/s\].
    pub critical_speed: f64,
    /// Damped natural frequencies of the Galerkin model (4.29) \[Hz\], ascending (only the
    /// modes that neither grow nor decay: none of a flutter pair is a natural frequency).
    pub analytical_hz: Vec<f64>,
    /// Damped natural frequencies of the flowing-material model (4.20) \[Hz\], ascending
    /// (likewise).
    pub flowing_hz: Vec<f64>,
    /// The exact frequencies of the travelling string with fixed ends for `|v| < c`,
    /// `f_n = n (c² − v²)/(2 c L)` \[Hz\] (Wickert & Mote 1990; Ribaric (4.30) converges to
    /// them), as many as reported; empty at and above the critical speed.
    pub exact_hz: Vec<f64>,
    /// Whether either model has a growing solution (an eigenvalue with positive real part):
    /// the string is unstable at and above the critical speed (Ribaric §4.2.3; a real
    /// positive eigenvalue, divergence, in the seed note's STR-5).
    pub unstable: bool,
    /// Growing solutions of the Galerkin model, fastest first (at most `report`).
    pub analytical_growth: Vec<Growth>,
    /// Growing solutions of the flowing-material model, fastest first (at most `report`).
    pub flowing_growth: Vec<Growth>,
    /// Largest relative deviation of `flowing_hz` from `exact_hz` (`None` at or above the
    /// critical speed).
    pub flowing_max_rel_error: Option<f64>,
    /// What the numbers cannot be trusted for: instability, frequencies not converged near
    /// the critical speed (the app prints these on stderr).
    pub warnings: Vec<String>,
    /// What the numbers mean.
    pub meaning: String,
}

/// Eigen analysis of the Galerkin model (4.29): (neutral frequencies \[Hz\], growth).
fn galerkin_spectrum(
    p: StringConfig,
    speed: f64,
    terms: usize,
) -> Result<(Vec<f64>, Vec<Growth>), FlowError> {
    let e = GalerkinString::new(p, speed, terms)?
        .system()
        .state_eigen()?;
    Ok((e.neutral_frequencies_hz(), growth(&e)))
}

/// Eigen analysis of the flowing-material model (4.20) with `modes` modes: (neutral
/// frequencies \[Hz\], growth).
fn flowing_spectrum(c: &ModesConfig, modes: usize) -> Result<(Vec<f64>, Vec<Growth>), FlowError> {
    let (_, sys) = flowing_model(c.string, c.nodes, modes, c.derivative, c.speed)?;
    let e = sys.frozen(c.speed, 0.0).state_eigen()?;
    Ok((e.neutral_frequencies_hz(), growth(&e)))
}

fn growth(e: &crate::gyroscopic::StateEigen) -> Vec<Growth> {
    e.growth_rates()
        .into_iter()
        .map(|(rate_per_s, frequency_hz)| Growth {
            rate_per_s,
            frequency_hz,
        })
        .collect()
}

/// `(index, relative error)` of the worst of `f` against `exact` (over their common length).
fn worst(f: &[f64], exact: &[f64]) -> Option<(usize, f64)> {
    f.iter()
        .zip(exact)
        .map(|(a, b)| (a - b).abs() / b.abs())
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// Run the modes study on a validated configuration: the first `c.report` natural
/// frequencies of the Galerkin model (4.29) and of the flowing-material model (4.20), their
/// growing solutions at and above the critical speed, and warnings where the flowing model's
/// frequencies are not converged (compared with the exact `f_n = n(c² − v²)/(2cL)`; the
/// flowing model is solved once more with twice the modes to say whether more modes help).
pub fn string_modes(c: &ModesConfig) -> Result<ModesSummary, FlowError> {
    let crit = c.string.wave_speed();
    let (mut analytical, mut a_growth) = galerkin_spectrum(c.string, c.speed, c.galerkin_terms)?;
    let (mut flowing, mut f_growth) = flowing_spectrum(c, c.modes)?;
    analytical.truncate(c.report);
    flowing.truncate(c.report);
    a_growth.truncate(c.report);
    f_growth.truncate(c.report);
    let unstable = !(a_growth.is_empty() && f_growth.is_empty());
    let subcritical = c.speed.abs() < crit;
    let exact: Vec<f64> = if subcritical {
        (1..=c.report)
            .map(|n| c.string.exact_moving_frequency_hz(n, c.speed))
            .collect()
    } else {
        Vec::new()
    };
    let mut warnings = Vec::new();
    if unstable {
        warnings.push(format!(
            "the axial speed {} m/s is {} the critical speed c = √(T/ρA) = {:.4} m/s: the \
             string is unstable (growth rates in analytical_growth and flowing_growth); the \
             frequencies listed are only the modes that neither grow nor decay",
            c.speed,
            if subcritical {
                "close to"
            } else {
                "at or above"
            },
            crit
        ));
    }
    let f_worst = worst(&flowing, &exact);
    if let Some((n, err)) = f_worst
        && err > CONVERGENCE_TOLERANCE
    {
        let more = (2 * c.modes).min(c.nodes);
        let hint = if more > c.modes {
            let (f2, _) = flowing_spectrum(c, more)?;
            match worst(&f2[..f2.len().min(c.report)], &exact) {
                Some((_, e2)) => format!(
                    "; with modes = {more} the worst of the first {} is {:.1} % off",
                    c.report,
                    100.0 * e2
                ),
                None => String::new(),
            }
        } else {
            String::new()
        };
        warnings.push(format!(
            "flowing_hz[{n}] (mode {}) is {:.1} % off the exact travelling-string frequency \
             n(c² − v²)/(2cL) = {:.4} Hz: {} retained modes do not converge at v/c = {:.3} \
             (near the critical speed the moving string's modes are far from the fixed \
             string's; raise `modes`){hint}",
            n + 1,
            100.0 * err,
            exact[n],
            c.modes,
            c.speed.abs() / crit
        ));
    }
    if let Some((n, err)) = worst(&analytical, &exact)
        && err > CONVERGENCE_TOLERANCE
    {
        warnings.push(format!(
            "analytical_hz[{n}] (mode {}) is {:.1} % off the exact frequency {:.4} Hz: raise \
             `galerkin_terms` ({} now)",
            n + 1,
            100.0 * err,
            exact[n],
            c.galerkin_terms
        ));
    }
    Ok(ModesSummary {
        speed: c.speed,
        critical_speed: crit,
        analytical_hz: analytical,
        flowing_hz: flowing,
        exact_hz: exact,
        unstable,
        analytical_growth: a_growth,
        flowing_growth: f_growth,
        flowing_max_rel_error: f_worst.map(|w| w.1),
        warnings,
        meaning: MODES_MEANING.to_string(),
    })
}

/// The modes study's "what the numbers mean" paragraph (`meaning` in the summary).
pub const MODES_MEANING: &str = "Natural frequencies of a string of length L, tension T and \
mass per length rho*A travelling at the axial speed v between two fixed guides (Ribaric \
ch. 4): analytical_hz from the Galerkin model (4.29), flowing_hz from the discrete \
flowing-material model (4.20), exact_hz from the closed form f_n = n(c^2 - v^2)/(2cL) with \
the wave speed c = sqrt(T/(rho*A)) = critical_speed. The axial motion lowers every frequency \
(Coriolis coupling of the modes); at v = c the lowest one reaches 0 Hz and above c the \
string is unstable: unstable = true, and analytical_growth / flowing_growth list the \
growing solutions (rate in 1/s: the amplitude grows as e^(rate*t); frequency 0 Hz is \
divergence, > 0 Hz flutter) instead of natural frequencies. flowing_max_rel_error is the \
flowing model's largest deviation from exact_hz; near c its modal basis (the fixed string's \
modes) converges slowly and a warning says when more modes are needed.";

#[cfg(test)]
mod tests {
    use super::*;

    // at rest the Galerkin and flowing frequencies approach the exact string's n·c/(2L)
    // (analytical, Ribaric (4.30) at v = 0)
    #[test]
    fn frequencies_at_rest_match_the_exact_string() {
        let c = ModesConfig {
            speed: 0.0,
            report: 3,
            ..Default::default()
        };
        c.validate().unwrap();
        let s = string_modes(&c).unwrap();
        for n in 1..=3 {
            let exact = c.string.exact_moving_frequency_hz(n, 0.0);
            assert!((s.analytical_hz[n - 1] - exact).abs() < 1e-6 * exact);
            assert!((s.flowing_hz[n - 1] - exact).abs() < 1e-2 * exact);
        }
    }

    // issue 20: at and above c = 40.27 m/s (41, 45, 60 m/s) the summary says unstable and
    // lists growth rates; reference: Ribaric §4.2.3 ("unstable for v > c") and the seed
    // note's STR-5 (divergence: a growing solution); below c nothing grows (invariant of
    // the undamped gyroscopic system: eigenvalues on the imaginary axis)
    #[test]
    fn supercritical_speeds_are_unstable_with_growth_rates() {
        for v in [41.0, 45.0, 60.0] {
            let c = ModesConfig {
                speed: v,
                ..Default::default()
            };
            let s = string_modes(&c).unwrap();
            assert!(s.unstable, "{v} m/s");
            assert!(!s.flowing_growth.is_empty() && !s.analytical_growth.is_empty());
            assert!(s.flowing_growth.iter().all(|g| g.rate_per_s > 0.0));
            assert!(s.exact_hz.is_empty() && s.flowing_max_rel_error.is_none());
            assert!(s.warnings[0].contains("unstable"), "{:?}", s.warnings);
        }
        for v in [0.0, 20.0, 39.0, -30.0] {
            let s = string_modes(&ModesConfig {
                speed: v,
                ..Default::default()
            })
            .unwrap();
            assert!(!s.unstable, "{v} m/s: {:?}", s.flowing_growth);
        }
    }

    // issue 20: at 39 m/s the default 20 modes leave the 10th frequency 21.6 % off the exact
    // f_n = n(c² − v²)/(2cL) (Wickert & Mote 1990), and the summary warns; 40 modes converge
    // to the mesh's own error (3.1 %, measured with all 99 modes), and the warning says so.
    // At 20 m/s nothing is off by more than 1 % and nothing is warned.
    #[test]
    fn unconverged_frequencies_near_critical_speed_are_warned() {
        let c = ModesConfig {
            speed: 39.0,
            ..Default::default()
        };
        let s = string_modes(&c).unwrap();
        let crit = c.string.wave_speed();
        for (n, f) in s.exact_hz.iter().enumerate() {
            let want = (n + 1) as f64 * crit * (1.0 - 39.0 * 39.0 / (crit * crit)) / 2.0;
            assert!((f - want).abs() < 1e-12 * want);
        }
        let err = s.flowing_max_rel_error.unwrap();
        assert!(err > 0.2 && err < 0.3, "{err}");
        let w = s.warnings.join(" | ");
        assert!(
            w.contains("mode 10") && w.contains("with modes = 40"),
            "{w}"
        );
        // the hint's figure: 40 modes bring the 10th frequency within 5 %
        let s40 = string_modes(&ModesConfig { modes: 40, ..c }).unwrap();
        assert!(s40.flowing_max_rel_error.unwrap() < CONVERGENCE_TOLERANCE);
        assert!(s40.warnings.is_empty(), "{:?}", s40.warnings);
        let s20 = string_modes(&ModesConfig::default()).unwrap();
        assert!(s20.flowing_max_rel_error.unwrap() < 0.01);
        assert!(s20.warnings.is_empty());
    }

    // the messages name the field (definition of the checks)
    #[test]
    fn bad_nodes_are_named() {
        let c = ModesConfig {
            nodes: 2,
            ..Default::default()
        };
        assert_eq!(c.validate().unwrap_err().field, "nodes");
    }
}
