//! `sweep`: frequencies against axial speed from 0 to past the critical speed.

use crate::common::*;
use flowing::{DerivativeMethod, StringConfig};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{InputError, Study, StudyContext, StudyError, Validate};
use serde::{Deserialize, Serialize};

/// Configuration.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SweepConfig {
    /// String parameters.
    pub string: StringConfig,
    /// Interior FE nodes.
    pub nodes: usize,
    /// Retained modes of the flowing-material model.
    pub modes: usize,
    /// Sine terms of the Galerkin model.
    pub galerkin_terms: usize,
    /// Highest speed as a multiple of the critical speed.
    pub max_speed_ratio: f64,
    /// Number of speeds (the default avoids hitting v = c exactly, where the stiffness vanishes
    /// and only the gyroscopic eigenvalues remain).
    pub steps: usize,
    /// Frequencies tracked per model.
    pub tracked: usize,
    /// Mode-shape derivative operator.
    pub derivative: DerivativeMethod,
}

impl Default for SweepConfig {
    fn default() -> Self {
        Self {
            string: StringConfig::default(),
            nodes: 99,
            modes: 20,
            galerkin_terms: 40,
            max_speed_ratio: 1.2,
            steps: 50,
            tracked: 5,
            derivative: DerivativeMethod::default(),
        }
    }
}

impl Validate for SweepConfig {
    fn validate(&self) -> Result<(), InputError> {
        check_string(&self.string, "string")?;
        check_nodes_modes(self.nodes, self.modes)?;
        if !(self.max_speed_ratio.is_finite() && self.max_speed_ratio > 1.0) {
            return Err(InputError::new(
                "max_speed_ratio",
                format!(
                    "must exceed 1 (past the critical speed), got {}",
                    self.max_speed_ratio
                ),
            ));
        }
        // one Galerkin and one flowing eigen problem per speed
        mbd_core::validate::check::size("steps", self.steps, 2, 100_000)?;
        mbd_core::validate::check::size(
            "galerkin_terms",
            self.galerkin_terms,
            1,
            MAX_GALERKIN_TERMS,
        )?;
        if self.tracked == 0 || self.tracked > self.modes {
            return Err(InputError::new(
                "tracked",
                format!("must be between 1 and modes = {}", self.modes),
            ));
        }
        if self.galerkin_terms < self.tracked {
            return Err(InputError::new(
                "galerkin_terms",
                "must be at least `tracked`",
            ));
        }
        Ok(())
    }
}

/// Summary.
#[derive(Debug, Clone, Serialize)]
pub struct SweepSummary {
    /// Critical speed \[m/s\].
    pub critical_speed: f64,
    /// Lowest swept speed at which the Galerkin model is unstable \[m/s\].
    pub analytical_unstable_from: Option<f64>,
    /// Lowest swept speed at which the flowing model is unstable \[m/s\].
    pub flowing_unstable_from: Option<f64>,
    /// Largest relative deviation of the flowing from the exact frequencies below 0.9 c.
    pub max_rel_error_below_0_9c: f64,
}

/// The `sweep` study.
pub struct SweepStudy {
    pub nodes: Option<usize>,
    pub modes: Option<usize>,
}

impl Study for SweepStudy {
    type Config = SweepConfig;
    type Summary = SweepSummary;
    const APP: &'static str = "string";
    const NAME: &'static str = "sweep";

    fn results_must_be_finite(&self) -> bool {
        true
    }

    fn meaning(&self) -> &'static str {
        "Natural frequencies of the travelling string (Ribaric ch. 4) against the axial speed \
         from 0 to max_speed_ratio times the critical speed c = sqrt(T/(rho A)) = \
         critical_speed [m/s] (sweep.csv, sweep.png): the Galerkin model (4.29), the \
         flowing-material model (4.20) and the exact f_n = n(c^2 - v^2)/(2cL). Every \
         frequency falls with the speed and the lowest reaches 0 Hz at v = c. \
         analytical_unstable_from / flowing_unstable_from are the lowest swept speeds at \
         which a model has a growing solution (an eigenvalue with positive real part, max_re \
         in sweep.csv [1/s]): the string is unstable from c on (shaded on the plot). \
         max_rel_error_below_0_9c is the flowing model's largest deviation from the exact \
         frequencies below 0.9 c; near c its modal basis converges slowly."
    }

    fn apply_overrides(&self, c: &mut SweepConfig) {
        if let Some(n) = self.nodes {
            c.nodes = n;
        }
        if let Some(k) = self.modes {
            c.modes = k;
        }
    }

    fn run(&self, c: &SweepConfig, ctx: &mut StudyContext) -> Result<SweepSummary, StudyError> {
        let crit = c.string.wave_speed();
        let (_, sys) = flowing_model(c.string, c.nodes, c.modes, c.derivative, 0.0)?;
        let mut header = vec!["speed_m_s".to_string()];
        for kind in ["analytical", "flowing", "exact"] {
            for n in 1..=c.tracked {
                header.push(format!("{kind}_f{n}_hz"));
            }
        }
        header.push("analytical_max_re_1_s".into());
        header.push("flowing_max_re_1_s".into());
        let hdr: Vec<&str> = header.iter().map(String::as_str).collect();
        let mut csv = ctx.out.csv("sweep.csv", &hdr)?;
        let bar = ctx.progress(c.steps as f64, "speed sweep");
        let mut series: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 2 * c.tracked];
        let (mut a_unst, mut f_unst, mut max_err) = (None, None, 0.0f64);
        for i in 0..c.steps {
            let v = c.max_speed_ratio * crit * i as f64 / (c.steps - 1) as f64;
            let (fa, ra) = galerkin_frequencies(c.string, v, c.galerkin_terms)?;
            let (ff, rf) = flowing_frequencies(&sys, v)?;
            let scale = 1e-6
                * (2.0 * std::f64::consts::PI * c.string.exact_moving_frequency_hz(c.tracked, 0.0));
            if ra > scale && a_unst.is_none() {
                a_unst = Some(v);
            }
            if rf > scale && f_unst.is_none() {
                f_unst = Some(v);
            }
            let mut row = vec![v];
            for (n, s) in series.iter_mut().enumerate().take(c.tracked) {
                row.push(fa.get(n).copied().unwrap_or(f64::NAN));
                if let Some(f) = fa.get(n) {
                    s.push((v, *f));
                }
            }
            for n in 0..c.tracked {
                row.push(ff.get(n).copied().unwrap_or(f64::NAN));
                if let Some(f) = ff.get(n) {
                    series[c.tracked + n].push((v, *f));
                }
                let ex = c.string.exact_moving_frequency_hz(n + 1, v);
                if v < 0.9 * crit
                    && let Some(f) = ff.get(n)
                {
                    max_err = max_err.max((f - ex).abs() / ex);
                }
            }
            for n in 0..c.tracked {
                row.push(c.string.exact_moving_frequency_hz(n + 1, v).max(0.0));
            }
            row.push(ra);
            row.push(rf);
            csv.row(&row)?;
            if ctx.tick(&bar, (i + 1) as f64).is_break() {
                // interrupted: the speeds swept so far make the summary
                break;
            }
        }
        csv.finish()?;
        bar.finish();
        let mut plot = LinePlot::new(
            "Travelling string: damped frequencies vs axial speed",
            "axial speed [m/s]",
            "frequency [Hz]",
        );
        for n in 0..c.tracked {
            plot = plot.with(Series::line(
                format!("Galerkin f{}", n + 1),
                series[n].clone(),
            ));
            plot = plot.with(Series::points(
                format!("flowing f{}", n + 1),
                series[c.tracked + n].clone(),
            ));
        }
        // the speeds at which either model has a growing solution (Ribaric §4.2.3: v > c)
        let from = match (a_unst, f_unst) {
            (Some(a), Some(f)) => Some(a.min(f)),
            (a, f) => a.or(f),
        };
        if let Some(v0) = from {
            let v_max = c.max_speed_ratio * crit;
            plot = plot.with_band(format!("unstable (from {v0:.2} m/s)"), v0, v_max);
        }
        plot.save(&ctx.out.path("sweep"))?;
        Ok(SweepSummary {
            critical_speed: crit,
            analytical_unstable_from: a_unst,
            flowing_unstable_from: f_unst,
            max_rel_error_below_0_9c: max_err,
        })
    }
}
