//! `flowmbd-tire dips`: the speed dips of the cleat test (Ribaric §8.3/§8.5: 40–50 km/h on
//! the drum, 45–55 km/h on the road), predicted from the cleat's quasi-static enveloping
//! profile and the loaded vertical mode (`tire::dips`) and measured by a cleat sweep,
//! on the drum and on the flat road.

use crate::cleat::validate_rig;
use crate::common::{RigFlags, TireSource, TireSourceExt, rig_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, run_study};
use serde::{Deserialize, Serialize};
use std::process::ExitCode;
use tire::{DipConfig, GroundDips, GroundKind, PulseShape, RigConfig, ground_dips};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: CommonArgs,
    #[command(flatten)]
    rig: RigFlags,
    /// Prediction only: no cleat sweep (overrides `dips.sweep_speeds_kmh` with none).
    #[arg(long)]
    no_sweep: bool,
    /// Only this ground (`drum` or `road`; default both).
    #[arg(long, value_parser = ["drum", "road"])]
    only: Option<String>,
    /// Pulse shape of the prediction: `half_sine` over the profile's support (default) or
    /// the `profile` itself (overrides `dips.pulse`).
    #[arg(long, value_parser = ["half_sine", "profile"])]
    pulse: Option<String>,
    /// Block the modes below this frequency in the enveloping profile (overrides
    /// `dips.blocked_below_hz`; 0 = quasi-static profile).
    #[arg(long)]
    blocked_below_hz: Option<f64>,
}

/// Configuration.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The tire.
    pub tire: TireSource,
    /// The rig (its ground kind and speed are replaced by each ground and sweep speed).
    pub rig: RigConfig,
    /// Profile, prediction and sweep settings.
    pub dips: DipConfig,
    /// Grounds studied.
    pub grounds: Vec<GroundKind>,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            rig: RigConfig::default(),
            dips: DipConfig::default(),
            grounds: vec![GroundKind::Drum, GroundKind::Road],
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.tire.validate()?;
        validate_rig(&self.rig)?;
        if !self.rig.ground.cleat {
            return Err(InputError::new(
                "rig.ground.cleat",
                "the dips need the cleat",
            ));
        }
        self.dips.validate_within("dips")?;
        if self.grounds.is_empty() {
            return Err(InputError::new("grounds", "is empty"));
        }
        Ok(())
    }
}

/// Summary of one ground.
#[derive(Debug, Serialize)]
pub struct GroundSummary {
    /// Ground.
    pub ground: GroundKind,
    /// Preload deflection \[m\].
    pub deflection_m: f64,
    /// Enveloping length of the model's profile \[m\].
    pub envelope_length_m: f64,
    /// Enveloping length of the undeformed tire's geometry \[m\].
    pub geometric_envelope_length_m: f64,
    /// Extent of the contact nodes along x \[m\].
    pub contact_node_span_m: [f64; 2],
    /// Peak quasi-static vertical force change \[N\].
    pub profile_peak_n: f64,
    /// Loaded vertical mode \[Hz\].
    pub vertical_mode_hz: f64,
    /// Its damping ratio.
    pub zeta: f64,
    /// Predicted dips \[km/h\].
    pub predicted_dips_kmh: Vec<f64>,
    /// Measured dips of the sweep \[km/h\].
    pub measured_dips_kmh: Vec<f64>,
    /// Measured line amplitude per sweep speed \[N\].
    pub line_amplitude_n: Vec<f64>,
    /// Sweep speeds \[km/h\].
    pub sweep_speeds_kmh: Vec<f64>,
}

/// Summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Per ground.
    pub grounds: Vec<GroundSummary>,
}

struct Dips {
    rig: RigFlags,
    no_sweep: bool,
    only: Option<String>,
    blocked_below_hz: Option<f64>,
    pulse: Option<String>,
}

fn name(k: GroundKind) -> &'static str {
    match k {
        GroundKind::Drum => "drum",
        GroundKind::Road => "road",
    }
}

/// Ribaric's dip band \[km/h\] (§8.5: drum 40–50, road 45–55).
fn ribaric_band(k: GroundKind) -> (f64, f64) {
    match k {
        GroundKind::Drum => (40.0, 50.0),
        GroundKind::Road => (45.0, 55.0),
    }
}

impl Study for Dips {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "tire";
    const NAME: &'static str = "dips";

    fn meaning(&self) -> &'static str {
        "The speed dips of the cleat test (Ribaric: 40-50 km/h on the drum, 45-55 km/h on the \
         road). Per ground: the quasi-static change of the vertical spindle force while the \
         cleat passes (profile_<ground>.csv; its extent is the enveloping length [m], against \
         the undeformed tire's geometric one), the loaded vertical mode [Hz] and its damping \
         ratio, the predicted ring-down amplitude of that mode after the cleat against speed \
         for a pulse over the enveloping length (dips.pulse: a half sine by default, or the \
         profile itself; prediction_<ground>.csv, dips where the pulse's spectrum has a zero \
         at the mode: v_k ~ f L/(k+1/2) for the half sine) and the measured amplitude of the vertical line in a cleat sweep \
         (sweep_<ground>.csv) with its local minima."
    }

    fn config_notes(&self, c: &Config) -> String {
        crate::common::import_notes(&c.tire)
    }

    fn apply_overrides(&self, c: &mut Config) {
        self.rig.apply(&mut c.tire, &mut c.rig);
        if self.no_sweep {
            c.dips.sweep_speeds_kmh.clear();
        }
        if let Some(p) = &self.pulse {
            c.dips.pulse = if p == "profile" {
                PulseShape::Profile
            } else {
                PulseShape::HalfSine
            };
        }
        if let Some(b) = self.blocked_below_hz {
            c.dips.blocked_below_hz = b;
        }
        if let Some(g) = &self.only {
            c.grounds = vec![if g == "road" {
                GroundKind::Road
            } else {
                GroundKind::Drum
            }];
        }
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let red = c.tire.reduced(ctx.quiet)?;
        let bar = ctx.progress(c.grounds.len() as f64, "dips");
        let mut out: Vec<GroundDips> = Vec::new();
        for (k, &g) in c.grounds.iter().enumerate() {
            let mut rig = c.rig.clone();
            rig.ground.kind = g;
            let d =
                ground_dips(&red, &rig, &c.dips, &mut |f| bar.set(k as f64 + f)).map_err(|e| {
                    match rig_err(e) {
                        StudyError::Numerical { message, .. } => StudyError::Numerical {
                            message: format!("{}: {message}", name(g)),
                            partial: None,
                        },
                        other => other,
                    }
                })?;
            out.push(d);
        }
        bar.finish();
        let mut profile_plot = LinePlot::new(
            "Quasi-static vertical force change while the cleat passes (spindle held)",
            "cleat ahead of the patch centre x [m]",
            "dFy [N]",
        );
        let mut amp_plot = LinePlot::new(
            "Vertical line against speed: predicted ring-down / sweep (each / its maximum)",
            "v [km/h]",
            "relative amplitude",
        );
        let mut grounds = Vec::new();
        for d in &out {
            let n = name(d.ground);
            let p = &d.profile;
            ctx.out.write_csv(
                &format!("profile_{n}.csv"),
                &["cleat_x_m", "dfy_N", "fx_N", "active_nodes_count"],
                (0..p.cleat_x.len())
                    .map(|i| vec![p.cleat_x[i], p.dfy[i], p.fx[i], p.active[i] as f64]),
            )?;
            let pr = &d.prediction;
            ctx.out.write_csv(
                &format!("prediction_{n}.csv"),
                &["speed_km_per_h", "amplitude_N"],
                pr.speeds_kmh
                    .iter()
                    .zip(&pr.amplitude_n)
                    .map(|(v, a)| vec![*v, *a]),
            )?;
            if !d.sweep_speeds_kmh.is_empty() {
                ctx.out.write_csv(
                    &format!("sweep_{n}.csv"),
                    &["speed_km_per_h", "line_amplitude_N"],
                    d.sweep_speeds_kmh
                        .iter()
                        .zip(&d.line_amplitude_n)
                        .map(|(v, a)| vec![*v, *a]),
                )?;
            }
            profile_plot = profile_plot.with(Series::line(
                n,
                p.cleat_x
                    .iter()
                    .copied()
                    .zip(p.dfy.iter().copied())
                    .collect(),
            ));
            let rel = |a: &[f64]| {
                let m = a.iter().copied().fold(0.0, f64::max).max(f64::MIN_POSITIVE);
                a.iter().map(|x| x / m).collect::<Vec<_>>()
            };
            amp_plot = amp_plot.with(Series::line(
                format!(
                    "{n}: predicted, {:.1} Hz, L = {:.3} m",
                    d.vertical_mode_hz, d.envelope_length_m
                ),
                pr.speeds_kmh
                    .iter()
                    .copied()
                    .zip(rel(&pr.amplitude_n))
                    .collect(),
            ));
            if !d.sweep_speeds_kmh.is_empty() {
                amp_plot = amp_plot.with(Series::points(
                    format!("{n}: sweep"),
                    d.sweep_speeds_kmh
                        .iter()
                        .copied()
                        .zip(rel(&d.line_amplitude_n))
                        .collect(),
                ));
            }
            let (a, b) = ribaric_band(d.ground);
            amp_plot = amp_plot.with_band(format!("Ribaric {n} dip"), a, b);
            grounds.push(GroundSummary {
                ground: d.ground,
                deflection_m: p.deflection,
                envelope_length_m: d.envelope_length_m,
                geometric_envelope_length_m: d.geometric_envelope_length_m,
                contact_node_span_m: p.node_span,
                profile_peak_n: p.dfy.iter().copied().fold(0.0, f64::max),
                vertical_mode_hz: d.vertical_mode_hz,
                zeta: d.zeta,
                predicted_dips_kmh: pr.dips_kmh.clone(),
                measured_dips_kmh: d.measured_dips_kmh.clone(),
                line_amplitude_n: d.line_amplitude_n.clone(),
                sweep_speeds_kmh: d.sweep_speeds_kmh.clone(),
            });
        }
        profile_plot.save(&ctx.out.path("profile"))?;
        amp_plot.save(&ctx.out.path("amplitude_vs_speed"))?;
        Ok(Summary { grounds })
    }
}

/// Run the study.
pub fn run(args: &Args) -> ExitCode {
    run_study(
        &Dips {
            rig: args.rig.clone(),
            no_sweep: args.no_sweep,
            only: args.only.clone(),
            blocked_below_hz: args.blocked_below_hz,
            pulse: args.pulse.clone(),
        },
        &args.common,
    )
}
