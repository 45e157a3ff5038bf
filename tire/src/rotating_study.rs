//! The rotating-modes study (`flowmbd-tire rotating-modes`, `flowmbd.tire.rotating_modes`):
//! complex modes of the rolling tire in the ground-fixed frame at several speeds
//! ([`modes_at_speed`]). The flowing-material gyroscopic and convective terms of Ribaric (7.17)
//! split each circumferential order `n` into a forward and a backward wave; the study reports
//! every mode of the free tire (rim fixed) and of the loaded tire (rolling preload's patch
//! held) per speed, and the forward/backward splits of the free tire's orders 1–8 (Campbell
//! diagram). Configuration, summary and the rows of `rotating_modes.csv` live here so that the
//! CLI and the Python package return the same numbers.

use crate::error::TireError;
use crate::ground::GroundConfig;
use crate::harmonics::WaveDirection;
use crate::reduced::ReducedTire;
use crate::rig::DampingConfig;
use crate::rotating::{RotatingMode, SpeedModes, modes_at_speed};
use crate::source::TireSource;
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Configuration of the rotating-modes study.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct RotatingStudyConfig {
    /// The tire.
    pub tire: TireSource,
    /// Rolling speeds \[km/h\].
    pub speeds_kmh: Vec<f64>,
    /// Modes up to this damped frequency \[Hz\].
    pub max_hz: f64,
    /// Ground of the loaded tire (drum R = 1.25 m by default; the cleat is not used).
    pub ground: GroundConfig,
    /// Vertical load \[N\] (1000 lb, Ribaric §8.3).
    pub load: f64,
    /// Include the cleat rig's Rayleigh damping (`damping`); false: undamped (conservative
    /// gyroscopic system, growth rates zero unless unstable).
    pub damped: bool,
    /// Rayleigh damping targets (the cleat rig's defaults).
    pub damping: DampingConfig,
}

impl Default for RotatingStudyConfig {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            speeds_kmh: vec![0.0, 30.0, 60.0, 90.0, 120.0],
            max_hz: 250.0,
            ground: GroundConfig::default(),
            load: 4448.2,
            damped: true,
            damping: DampingConfig::default(),
        }
    }
}

impl mbd_core::config::PartialRules for RotatingStudyConfig {}

impl Validate for RotatingStudyConfig {
    /// At least one finite speed ≥ 0, a positive `max_hz` and `load`, the ground, the damping
    /// targets and the tire.
    fn validate(&self) -> Result<(), InvalidField> {
        if self.speeds_kmh.is_empty() {
            return Err(InvalidField::new(
                "speeds_kmh",
                "must list at least one speed",
            ));
        }
        if let Some(v) = self
            .speeds_kmh
            .iter()
            .find(|v| !(v.is_finite() && **v >= 0.0))
        {
            return Err(InvalidField::new("speeds_kmh", format!("{v} is not ≥ 0")));
        }
        if !(self.max_hz > 0.0 && self.max_hz.is_finite()) {
            return Err(InvalidField::new("max_hz", "must be positive"));
        }
        if !(self.load > 0.0 && self.load.is_finite()) {
            return Err(InvalidField::new("load", "must be positive"));
        }
        self.ground.validate_within("ground")?;
        self.damping.validate_within("damping")?;
        self.tire.validate_within("tire")
    }
}

/// One mode in the summary.
#[derive(Debug, Clone, Serialize)]
pub struct ModeOut {
    /// Damped frequency in the ground frame \[Hz\].
    pub hz: f64,
    /// Circumferential order.
    pub n: usize,
    /// `forward` (with the rotation), `backward` or `standing`.
    pub direction: WaveDirection,
    /// Damping ratio `−Re λ/|λ|`.
    pub damping_ratio: f64,
    /// Growth rate `Re λ` \[1/s\].
    pub growth_rate: f64,
    /// Undamped frequency `|λ|/2π` \[Hz\].
    pub natural_hz: f64,
    /// Signed travelling share (+1 forward, −1 backward).
    pub travelling: f64,
    /// Lateral (out-of-plane) fraction of the order-n tread motion.
    pub lateral_share: f64,
}

impl From<&RotatingMode> for ModeOut {
    fn from(m: &RotatingMode) -> Self {
        Self {
            hz: m.hz,
            n: m.n,
            direction: m.direction,
            damping_ratio: m.damping_ratio,
            growth_rate: m.growth_rate,
            natural_hz: m.natural_hz,
            travelling: m.travelling,
            lateral_share: m.parts[2],
        }
    }
}

/// The modes at one speed.
#[derive(Debug, Clone, Serialize)]
pub struct SpeedOut {
    /// Speed \[km/h\].
    pub speed_kmh: f64,
    /// Spin rate \[rad/s\].
    pub spin_rad_s: f64,
    /// Free tire (rim fixed), ascending.
    pub free: Vec<ModeOut>,
    /// Contact nodes held in the loaded tire.
    pub loaded_held_nodes: usize,
    /// Loaded tire (patch held), ascending.
    pub loaded: Vec<ModeOut>,
}

/// The forward/backward pair of one order of the free tire across the speeds.
#[derive(Debug, Clone, Serialize)]
pub struct SplitOut {
    /// Circumferential order.
    pub n: usize,
    /// `in_plane` or `lateral`.
    pub plane: &'static str,
    /// Frequency of the lowest pair of this order and plane at zero speed \[Hz\].
    pub zero_speed_hz: f64,
    /// Forward frequency per speed \[Hz\] (`null` where not found; at zero speed the pair is
    /// degenerate and both are the standing frequency).
    pub forward_hz: Vec<Option<f64>>,
    /// Backward frequency per speed \[Hz\].
    pub backward_hz: Vec<Option<f64>>,
    /// Split `forward − backward` per speed \[Hz\].
    pub split_hz: Vec<Option<f64>>,
}

/// Summary of the rotating-modes study (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct RotatingSummary {
    /// The modes per speed.
    pub speeds: Vec<SpeedOut>,
    /// The forward/backward splits of the free tire's orders 1..=8 (lowest pair per order and
    /// plane).
    pub splits: Vec<SplitOut>,
    /// Largest relative difference of the zero-speed natural frequencies of the free tire from
    /// `flowmbd-tire modes`' reduced frequencies (when 0 is among the speeds).
    pub zero_speed_max_rel_diff_vs_modes: Option<f64>,
    /// Rayleigh α \[1/s\], β \[s\] used.
    pub rayleigh: [f64; 2],
    /// What the numbers mean ([`ROTATING_MEANING`]).
    pub meaning: String,
}

/// The rotating-modes study's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const ROTATING_MEANING: &str = "Complex modes of the rolling tire seen from the ground at every speed (Campbell \
     diagram): each mode's frequency [Hz], circumferential order n, direction (forward or \
     backward travelling wave), damping ratio and growth rate [1/s]. At rest the modes of \
     order n >= 1 come in pairs of equal frequency; rolling splits each pair into a \
     forward and a backward wave (splits: the split grows linearly with speed, as for a \
     spinning ring). zero_speed_max_rel_diff_vs_modes compares the speed-0 frequencies \
     with the modes study (a second path to the same numbers); rayleigh holds the damping \
     used (alpha [1/s], beta [s]).";

/// Whether a mode is lateral (out-of-plane share above one half).
fn lateral(m: &RotatingMode) -> bool {
    m.parts[2] > 0.5
}

/// The lowest forward/backward pair of order `n` and plane `lat` at one speed whose mean is
/// nearest the zero-speed frequency `f0` (the Ω² terms move the mean only slightly).
fn pair_at(modes: &[RotatingMode], n: usize, lat: bool, f0: f64) -> Option<(f64, f64)> {
    let of = |d: WaveDirection| {
        modes
            .iter()
            .filter(move |m| m.n == n && lateral(m) == lat && m.direction == d)
    };
    let mut best: Option<(f64, f64, f64)> = None;
    for f in of(WaveDirection::Forward) {
        for b in of(WaveDirection::Backward) {
            let e = (0.5 * (f.hz + b.hz) - f0).abs();
            if best.is_none_or(|x| e < x.2) {
                best = Some((f.hz, b.hz, e));
            }
        }
    }
    best.filter(|x| x.2 < 0.15 * f0).map(|x| (x.0, x.1))
}

/// The forward/backward splits of the free tire's orders 1..=8 per plane across `runs`: the
/// zero-speed frequency is the lowest standing mode of the slowest run when it is at rest,
/// otherwise the mean of its lowest pair; at each speed the pair whose mean is nearest it
/// (within 15 %).
pub fn splits(runs: &[SpeedModes]) -> Vec<SplitOut> {
    let Some(first) = runs.iter().min_by(|a, b| a.spin.total_cmp(&b.spin)) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for n in 1..=8 {
        for lat in [false, true] {
            let f0 = if first.spin == 0.0 {
                first
                    .free
                    .iter()
                    .find(|m| m.n == n && lateral(m) == lat)
                    .map(|m| m.hz)
            } else {
                let fwd = first.free.iter().find(|m| {
                    m.n == n && lateral(m) == lat && m.direction == WaveDirection::Forward
                });
                let bwd = first.free.iter().find(|m| {
                    m.n == n && lateral(m) == lat && m.direction == WaveDirection::Backward
                });
                fwd.zip(bwd).map(|(f, b)| 0.5 * (f.hz + b.hz))
            };
            let Some(f0) = f0 else { continue };
            let (mut fw, mut bw, mut sp) = (Vec::new(), Vec::new(), Vec::new());
            for r in runs {
                let p = if r.spin == 0.0 {
                    Some((f0, f0))
                } else {
                    pair_at(&r.free, n, lat, f0)
                };
                fw.push(p.map(|p| p.0));
                bw.push(p.map(|p| p.1));
                sp.push(p.map(|p| p.0 - p.1));
            }
            out.push(SplitOut {
                n,
                plane: if lat { "lateral" } else { "in_plane" },
                zero_speed_hz: f0,
                forward_hz: fw,
                backward_hz: bw,
                split_hz: sp,
            });
        }
    }
    out
}

/// The direction as a number of `rotating_modes.csv`: +1 forward, −1 backward, 0 standing.
pub fn direction_code(d: WaveDirection) -> f64 {
    match d {
        WaveDirection::Forward => 1.0,
        WaveDirection::Backward => -1.0,
        WaveDirection::Standing => 0.0,
    }
}

/// Run the study on the reduced tire `red`: the Rayleigh coefficients of `c.damping` (when
/// `c.damped`), then [`modes_at_speed`] at every speed; `progress` gets the fraction done
/// (0–1). Returns the summary and the modes per speed (for plots).
pub fn run_rotating(
    red: &ReducedTire, c: &RotatingStudyConfig, progress: &mut dyn FnMut(f64),
) -> Result<(RotatingSummary, Vec<SpeedModes>), TireError> {
    let rayleigh = if c.damped {
        let r = c.damping.rayleigh(red)?;
        (r.alpha, r.beta)
    } else {
        (0.0, 0.0)
    };
    let mut runs = Vec::with_capacity(c.speeds_kmh.len());
    let n = c.speeds_kmh.len().max(1) as f64;
    for (k, &v) in c.speeds_kmh.iter().enumerate() {
        runs.push(modes_at_speed(
            red, &c.ground, c.load, v, rayleigh, c.max_hz,
        )?);
        progress((k + 1) as f64 / n);
    }
    let splits = splits(&runs);
    let zero = runs.iter().find(|r| r.spin == 0.0).map(|r| {
        let f = red.frequencies_hz().unwrap_or_default();
        r.free
            .iter()
            .zip(&f)
            .map(|(m, f)| (m.natural_hz - f).abs() / f)
            .fold(0.0, f64::max)
    });
    let summary = RotatingSummary {
        speeds: runs
            .iter()
            .map(|r| SpeedOut {
                speed_kmh: r.speed_kmh,
                spin_rad_s: r.spin,
                free: r.free.iter().map(ModeOut::from).collect(),
                loaded_held_nodes: r.held_nodes,
                loaded: r.loaded.iter().map(ModeOut::from).collect(),
            })
            .collect(),
        splits,
        zero_speed_max_rel_diff_vs_modes: zero,
        rayleigh: [rayleigh.0, rayleigh.1],
        meaning: ROTATING_MEANING.to_string(),
    };
    Ok((summary, runs))
}

/// Columns of `rotating_modes.csv` (one row per mode: speed \[km/h\], 0 free / 1 loaded, damped
/// frequency \[Hz\], order, [`direction_code`], damping ratio, growth rate \[1/s\], natural
/// frequency \[Hz\], travelling share, lateral share).
pub const ROTATING_COLUMNS: [&str; 10] = [
    "speed_km_per_h",
    "loaded_flag",
    "f_Hz",
    "n",
    "direction_code",
    "damping_ratio",
    "growth_rate_1_per_s",
    "natural_Hz",
    "travelling_share",
    "lateral_share",
];

/// The rows of `rotating_modes.csv` ([`ROTATING_COLUMNS`]): per speed the free modes, then the
/// loaded ones.
pub fn rotating_rows(s: &RotatingSummary) -> Vec<[f64; 10]> {
    s.speeds
        .iter()
        .flat_map(|r| {
            [(0.0, &r.free), (1.0, &r.loaded)]
                .into_iter()
                .flat_map(move |(l, modes)| {
                    modes.iter().map(move |m| {
                        [
                            r.speed_kmh,
                            l,
                            m.hz,
                            m.n as f64,
                            direction_code(m.direction),
                            m.damping_ratio,
                            m.growth_rate,
                            m.natural_hz,
                            m.travelling,
                            m.lateral_share,
                        ]
                    })
                })
        })
        .collect()
}
