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
    check::count("nodes", nodes, 3, MAX_STRING_NODES)?;
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
    if n > max {
        return Err(InvalidField::new(
            field,
            format!(
                "{} s in steps of {} s is {n:.3e} {what}, more than the {max:e} a run may take",
                check::show(duration),
                check::show(step)
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
        check::count("galerkin_terms", self.galerkin_terms, 1, MAX_GALERKIN_TERMS)?;
        if self.report == 0 {
            return Err(InvalidField::new("report", "must be at least 1"));
        }
        Ok(())
    }
}

/// Summary of the modes study (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct ModesSummary {
    /// Axial speed \[m/s\].
    pub speed: f64,
    /// Critical speed `c = √(T/ρA)` \[m/s\].
    pub critical_speed: f64,
    /// Damped natural frequencies of the Galerkin model (4.29) \[Hz\], ascending.
    pub analytical_hz: Vec<f64>,
    /// Damped natural frequencies of the flowing-material model (4.20) \[Hz\], ascending.
    pub flowing_hz: Vec<f64>,
}

/// Run the modes study on a validated configuration: the first `c.report` damped frequencies
/// of the Galerkin model (4.29) and of the flowing-material model (4.20).
pub fn string_modes(c: &ModesConfig) -> Result<ModesSummary, FlowError> {
    let (mut analytical, _) = galerkin_frequencies(c.string, c.speed, c.galerkin_terms)?;
    let (_, sys) = flowing_model(c.string, c.nodes, c.modes, c.derivative, c.speed)?;
    let (mut flowing, _) = flowing_frequencies(&sys, c.speed)?;
    analytical.truncate(c.report);
    flowing.truncate(c.report);
    Ok(ModesSummary {
        speed: c.speed,
        critical_speed: c.string.wave_speed(),
        analytical_hz: analytical,
        flowing_hz: flowing,
    })
}

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
