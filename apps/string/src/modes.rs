//! `modes`: damped natural frequencies of the analytical and the flowing-material models.

use crate::common::*;
use flowing::{DerivativeMethod, StringConfig};
use flowmbd_cli::{InputError, Study, StudyContext, StudyError, Validate};
use serde::{Deserialize, Serialize};

/// Configuration (defaults: Ribaric 4.2.3 string at 20 m/s, 99 nodes, 20 modes).
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
    fn validate(&self) -> Result<(), InputError> {
        check_string(&self.string, "string")?;
        check_number("speed", self.speed, false)?;
        check_nodes_modes(self.nodes, self.modes)?;
        if self.galerkin_terms == 0 {
            return Err(InputError::new("galerkin_terms", "must be at least 1"));
        }
        if self.report == 0 {
            return Err(InputError::new("report", "must be at least 1"));
        }
        Ok(())
    }
}

/// Summary printed by `--json`.
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

/// The `modes` study.
pub struct ModesStudy {
    pub speed: Option<f64>,
    pub nodes: Option<usize>,
    pub modes: Option<usize>,
}

impl Study for ModesStudy {
    type Config = ModesConfig;
    type Summary = ModesSummary;
    const APP: &'static str = "string";
    const NAME: &'static str = "modes";

    fn apply_overrides(&self, c: &mut ModesConfig) {
        if let Some(v) = self.speed {
            c.speed = v;
        }
        if let Some(n) = self.nodes {
            c.nodes = n;
        }
        if let Some(k) = self.modes {
            c.modes = k;
        }
    }

    fn run(&self, c: &ModesConfig, ctx: &mut StudyContext) -> Result<ModesSummary, StudyError> {
        let (mut analytical, _) = galerkin_frequencies(c.string, c.speed, c.galerkin_terms)?;
        let (_, sys) = flowing_model(c.string, c.nodes, c.modes, c.derivative, c.speed)?;
        let (mut flowing, _) = flowing_frequencies(&sys, c.speed)?;
        analytical.truncate(c.report);
        flowing.truncate(c.report);
        let exact: Vec<f64> = (1..=c.report)
            .map(|n| c.string.exact_moving_frequency_hz(n, c.speed))
            .collect();
        let rows = (0..c.report).map(|i| {
            [
                (i + 1) as f64,
                analytical.get(i).copied().unwrap_or(f64::NAN),
                flowing.get(i).copied().unwrap_or(f64::NAN),
                exact[i],
            ]
        });
        ctx.out.write_csv(
            "frequencies.csv",
            &["n", "analytical_hz", "flowing_hz", "exact_hz"],
            rows,
        )?;
        Ok(ModesSummary {
            speed: c.speed,
            critical_speed: c.string.wave_speed(),
            analytical_hz: analytical,
            flowing_hz: flowing,
        })
    }
}
